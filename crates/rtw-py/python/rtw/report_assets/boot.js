"use strict";
// What both rtw pages share: the scan report (report.js) and the design page
// (design.js) are each this file followed by the page's own script, which
// ends by calling boot(main). Plotly.js and the page's data are inlined
// gzipped (base64) and inflated here with the browser's DecompressionStream.
window.rtwReport = { ready: false, selected: null, frame: null, timings: {} };
// Each step is a Performance API mark "rtw:NAME" (scripts/report_timing.py reads them).
const mark = (name) => { window.rtwReport.timings[name] = Math.round(performance.mark(`rtw:${name}`).startTime); };

async function inflate(id) {
  const b64 = document.getElementById(id).textContent.trim();
  let bytes;
  if (Uint8Array.fromBase64) {
    bytes = Uint8Array.fromBase64(b64);  // Chromium >= 140, Firefox >= 133, Safari >= 18.2
  } else {
    const bin = atob(b64);
    bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
  }
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
  return await new Response(stream).text();
}

// The folder's figures (and animations), inlined as data URLs, under #images.
function showImages(images, width) {
  if (!images.length) return;
  document.getElementById("images-section").hidden = false;
  const box = document.getElementById("images");
  images.forEach((im) => {
    const f = document.createElement("figure");
    const img = document.createElement("img"); img.src = im.src; img.style.maxWidth = `${width}px`;
    const cap = document.createElement("figcaption"); cap.textContent = im.name;
    f.append(img, cap); box.appendChild(f);
  });
}

// Inflates Plotly and the data, runs the page's main(data), and says when
// everything is drawn (window.rtwReport.ready) or why it could not be.
function boot(main) {
  (async () => {
    const status = document.getElementById("status");
    try {
      const [lib, text] = await Promise.all([inflate("plotly-gz"), inflate("data-gz")]);
      mark("inflated");
      const el = document.createElement("script");
      el.textContent = lib;
      document.head.appendChild(el);
      mark("plotly");
      await main(JSON.parse(text));
      status.textContent = "";
      mark("ready");
      window.rtwReport.readyMs = performance.now();
      window.rtwReport.ready = true;
    } catch (e) {
      status.textContent = `The report could not be drawn: ${e}`;
      console.error(e);
    }
  })();
}
