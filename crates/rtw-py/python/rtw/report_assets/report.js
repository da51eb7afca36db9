// The scan report of `python -m rtw report` (crates/rtw-py/python/rtw/report.py),
// after boot.js. Everything about the robot (rods, strings, feet, ground,
// view) arrives as world-frame coordinates computed in Python by rtw.draw:
// this script only draws segments and points.
const LABEL = {
  length: "L [m]", rho: "ρ [kg/m]", alpha: "α", fn: "f_n [Hz]", zeta: "ζ", phi: "φ [rad]",
  speed: "speed [m/s]", f_w: "f_w [Hz]", mu_required: "μ required", outcome: "outcome",
};
const label = (c) => LABEL[c] || c;
const fmt = (v) => (v === null || v === undefined) ? "none"
  : (typeof v === "number" ? (Number.isInteger(v) ? String(v) : v.toPrecision(6)) : String(v));

// A colour per category on a numeric colour axis [-0.5, K - 0.5].
function stepped(colors) {
  const K = colors.length, s = [];
  colors.forEach((c, k) => { s.push([k / K, c]); s.push([(k + 1) / K, c]); });
  return s;
}

// Resolves once the browser has painted what is drawn so far (a frame's
// callback runs before its paint, a task queued from it after): the page shows
// its first view (header, summary, gait map) before the views further down.
const paint = () => new Promise((resolve) => requestAnimationFrame(() => setTimeout(resolve, 0)));

// A base64 string's bytes, decoded once per string.
const decoded = new Map();
function bytes(b64) {
  if (!decoded.has(b64)) decoded.set(b64, Uint8Array.from(atob(b64), (ch) => ch.charCodeAt(0)));
  return decoded.get(b64);
}

// Brushing over every row of a large scan, from its coded columns: a row is
// picked when, on every brushed axis, its bin [lo + k·w, lo + (k + 1)·w]
// meets a brushed range (the "none" position for a row without a value).
function countCoded(D, cols, ranges, per, picked) {
  const B = D.big, out = bytes(B.outcome), n = D.n;
  const tests = [];
  cols.forEach((c, j) => {
    const r = ranges[j];
    if (!r) return;
    const [lo, hi] = D.ranges[c] || [0, 1];
    const w = (hi - lo) / B.bins, none = lo - 0.1 * ((hi - lo) || 1);
    const ok = new Uint8Array(256);
    for (let k = 0; k < B.bins; k++) {
      const a = hi > lo ? lo + k * w : lo, b = hi > lo ? lo + (k + 1) * w : lo;
      ok[k] = r.some(([x, y]) => a <= y && b >= x) ? 1 : 0;
    }
    ok[B.none] = r.some(([x, y]) => none >= x && none <= y) ? 1 : 0;
    tests.push([bytes(B.codes[c]), ok]);
  });
  let total = 0;
  for (let i = 0; i < n; i++) {
    let yes = 1;
    for (let t = 0; t < tests.length && yes; t++) yes = tests[t][1][tests[t][0][i]];
    if (yes) { total++; per[out[i]]++; picked[i] = 1; }
  }
  return total;
}

// A density of rows per group on an nb × nb grid (row-major, y up) as a PNG
// data URL: each cell the mix of its groups' colours, more opaque with more
// rows (log scale), empty cells transparent.
function densityPng(grids, colors, nb) {
  const rgb = colors.map((c) => { const e = document.createElement("canvas").getContext("2d"); e.fillStyle = c;
    const h = e.fillStyle; return [1, 3, 5].map((k) => parseInt(h.slice(k, k + 2), 16)); });
  const canvas = document.createElement("canvas");
  canvas.width = nb; canvas.height = nb;
  const ctx = canvas.getContext("2d"), img = ctx.createImageData(nb, nb);
  let most = 0;
  const tot = new Float64Array(nb * nb);
  grids.forEach((g) => g.forEach((v, q) => { tot[q] += v; }));
  tot.forEach((v) => { if (v > most) most = v; });
  for (let yb = 0; yb < nb; yb++) for (let xb = 0; xb < nb; xb++) {
    const q = yb * nb + xb, t = tot[q];
    if (!t) continue;
    const p = ((nb - 1 - yb) * nb + xb) * 4; // image rows run downwards
    let r = 0, g = 0, b = 0;
    grids.forEach((grid, k) => { const f = grid[q] / t; r += f * rgb[k][0]; g += f * rgb[k][1]; b += f * rgb[k][2]; });
    img.data[p] = r; img.data[p + 1] = g; img.data[p + 2] = b;
    img.data[p + 3] = 60 + 195 * Math.log1p(t) / Math.log1p(most);
  }
  ctx.putImageData(img, 0, 0);
  return canvas.toDataURL("image/png");
}

// A coded column's range as a map's axis: a column of one value (held fixed
// by the scan, all in the middle bin) widened both ways, so it is drawn at
// its value.
const axisOf = ([lo, hi]) => (hi > lo ? [lo, hi] : [lo - 0.05 * (Math.abs(lo) || 1), lo + 0.05 * (Math.abs(lo) || 1)]);

// A layout image covering [x0, x1] × [y0, y1] of a plot's axes.
const imageOn = (src, [x0, x1], [y0, y1]) => [{ source: src, xref: "x", yref: "y", x: x0, y: y1, sizex: x1 - x0,
  sizey: y1 - y0, sizing: "stretch", layer: "below" }];

// The gait map of a large scan: every row on the grid of its α and f_n bins
// (densityPng, by outcome); the gaits as clickable marks.
async function densityMap(gm, D, ocolor, cfg) {
  const B = D.big, G = B.density, nb = B.bins;
  const [x0, x1] = axisOf(D.ranges[G.x]), [y0, y1] = axisOf(D.ranges[G.y]);
  const image = (grids) => imageOn(densityPng(grids, ocolor, nb), [x0, x1], [y0, y1]);
  const rowOf = new Map(D.columns.sample_id.map((s, i) => [s, i]));
  const gaits = D.gaits.map((g) => rowOf.get(g.sample_id));
  await Plotly.newPlot(gm, [
    ...D.outcomes.map((o, k) => ({ type: "scatter", mode: "markers", name: o, x: [null], y: [null],
      marker: { color: ocolor[k], size: 10, symbol: "square" }, hoverinfo: "skip" })),
    { type: "scatter", mode: "markers", name: "gaits (click)", customdata: gaits,
      x: gaits.map((i) => D.columns[G.x][i]), y: gaits.map((i) => D.columns[G.y][i]),
      text: gaits.map((i) => D.columns.sample_id[i]),
      marker: { color: gaits.map((i) => ocolor[D.outcome[i]]), size: 9, line: { color: "black", width: 1.5 } },
      hovertemplate: "sample %{text}<extra>gait</extra>" },
  ], { images: image(G.grids),
       xaxis: { title: { text: "α" }, range: [x0, x1] }, yaxis: { title: { text: "f_n [Hz]" }, range: [y0, y1] },
       margin: { t: 20 }, legend: { title: { text: "outcome" } } }, cfg);
  // Brushing re-bins the picked rows from their codes (null: every row).
  const cx = bytes(B.codes[G.x]), cy = bytes(B.codes[G.y]), out = bytes(B.outcome);
  gm.redraw = (picked) => {
    if (!picked) { Plotly.relayout(gm, { images: image(G.grids) }); return; }
    const grids = G.grids.map(() => new Uint32Array(nb * nb));
    for (let i = 0; i < D.n; i++) {
      if (picked[i] && cx[i] !== B.none && cy[i] !== B.none) grids[out[i]][cy[i] * nb + cx[i]]++;
    }
    Plotly.relayout(gm, { images: image(grids) });
  };
}

async function main(D) {
  const S = D.style;
  const K = D.outcomes.length;
  const ocolor = D.outcomes.map((o) => S.outcome[o] || "#999");
  const cfg = { displaylogo: false, responsive: true };
  // SVG draws a few thousand points faster than a new WebGL context starts; WebGL beyond.
  const scatter = (m) => (m > 5000 ? "scattergl" : "scatter");
  // The rows drawn: all of them, or above a limit a seeded random subset chosen
  // in Python (the same in every view); counts are always of every row.
  // The rows the page holds one by one: all of them, or above PLOT_ROWS rows
  // (D.big) a stratified sample's, with every row coded a byte per plotted
  // column (bytes below): the maps and the counts are then of every row.
  const shown = Array.from({ length: D.big ? D.big.rows : D.n }, (_, i) => i);
  document.getElementById("drawn").textContent = D.big
    ? `The gait map shows every one of the ${D.n.toLocaleString("en")} samples as a density (each cell `
      + "coloured by the outcomes in it, darker with more samples). The views with a mark per sample draw "
      + `${shown.length.toLocaleString("en")} of them (the same ones in every view): each outcome an equal share, `
      + "an outcome with fewer samples all of them. The counts are of every sample."
    : `The views draw every one of the ${D.n.toLocaleString("en")} samples.`;

  const byOutcome = D.outcomes.map(() => []);
  shown.forEach((i) => byOutcome[D.outcome[i]].push(i));

  // ---- the gait map first: with the header and the summary it is the first
  // view. Up to 5 000 points it is SVG, which draws before a WebGL context
  // (software-rendered without a GPU) would have started.
  const A = D.columns.alpha, F = D.columns.fn, PHI = D.columns.phi;
  const sid = D.columns.sample_id;
  const hover = "sample %{text}<br>α %{x:.4f}<br>f_n %{y:.3f}<extra>%{fullData.name}</extra>";
  const gm = document.getElementById("gaitmap");
  if (D.big) await densityMap(gm, D, ocolor, cfg); else await Plotly.newPlot(gm, D.outcomes.map((o, k) => ({
    type: scatter(shown.length), mode: "markers", name: o, x: byOutcome[k].map((i) => A[i]), y: byOutcome[k].map((i) => F[i]),
    customdata: byOutcome[k], text: byOutcome[k].map((i) => sid[i]), marker: { color: ocolor[k], size: shown.length > 5000 ? 3 : 6, opacity: 0.8 },
    unselected: { marker: { opacity: 0.08 } },
    hovertemplate: hover,
  })), { xaxis: { title: { text: label("alpha") } }, yaxis: { title: { text: label("fn") } },
         margin: { t: 20 }, legend: { title: { text: "outcome" } } }, cfg);


  // ---- a sample: its columns and its gait.
  const gaitOf = new Map(D.gaits.map((g) => [g.sample_id, g]));
  const gbox = document.getElementById("gaits");
  const rowOf = new Map(sid.map((s, i) => [s, i]));
  D.gaits.forEach((g) => {
    const b = document.createElement("button");
    b.textContent = `#${g.sample_id} ${g.outcome}: ${g.why}`;
    b.onclick = () => showSample(rowOf.get(g.sample_id));
    gbox.appendChild(b);
  });
  const canvas = document.getElementById("gait-canvas");
  const ctx = canvas.getContext("2d");
  const frameEl = document.getElementById("frame");
  const noteEl = document.getElementById("gait-note");
  let anim = null;
  let playing = true;
  document.getElementById("play").onclick = (e) => {
    playing = !playing; e.target.textContent = playing ? "pause" : "play";
    if (anim) anim.t0 = performance.now() - anim.k * anim.dt * 1000;
  };

  function drawFrame(g, k) {
    const W = canvas.width, H = canvas.height, s = W / g.window;
    const [cx, cy] = g.centre[k];
    const X = (x) => W / 2 + (x - cx) * s, Y = (y) => H / 2 - (y - cy) * s;
    ctx.clearRect(0, 0, W, H);
    // The slope: a line along the ground direction through the origin, earth below, marks every 0.2 m.
    const [gx, gy] = g.ground, [nx, ny] = g.normal;
    const tc = cx * gx + cy * gy, R = g.window * 1.5, depth = 0.6 * g.length;
    const p = (t) => [t * gx, t * gy];
    const [a0, a1] = [p(tc - R), p(tc + R)];
    ctx.fillStyle = S.earth; ctx.beginPath();
    ctx.moveTo(X(a0[0]), Y(a0[1])); ctx.lineTo(X(a1[0]), Y(a1[1]));
    ctx.lineTo(X(a1[0] - depth * nx), Y(a1[1] - depth * ny)); ctx.lineTo(X(a0[0] - depth * nx), Y(a0[1] - depth * ny));
    ctx.closePath(); ctx.fill();
    ctx.strokeStyle = S.ground; ctx.lineWidth = 2; ctx.beginPath();
    ctx.moveTo(X(a0[0]), Y(a0[1])); ctx.lineTo(X(a1[0]), Y(a1[1])); ctx.stroke();
    ctx.lineWidth = 1;
    for (let t = Math.ceil((tc - R) / 0.2) * 0.2; t <= tc + R; t += 0.2) {
      const q = p(t); ctx.beginPath(); ctx.moveTo(X(q[0]), Y(q[1]));
      ctx.lineTo(X(q[0] - 0.04 * depth * nx), Y(q[1] - 0.04 * depth * ny)); ctx.stroke();
    }
    const seg = (v, color, width) => {
      ctx.strokeStyle = color; ctx.lineWidth = width; ctx.lineCap = "round"; ctx.beginPath();
      ctx.moveTo(X(v[0]), Y(v[1])); ctx.lineTo(X(v[2]), Y(v[3])); ctx.stroke();
    };
    g.strings[k].forEach((v) => seg(v, S.string, 1.2));
    g.rods[k].forEach((v, r) => seg(v, S.rod[r], 5));
    g.feet[k].forEach(([x, y], r) => {
      const m = g.mode[k][r];
      if (m === 0) return;
      ctx.lineWidth = 1.5; ctx.strokeStyle = "black"; ctx.beginPath();
      if (m === 1) { ctx.fillStyle = "black"; ctx.arc(X(x), Y(y), 5, 0, 2 * Math.PI); }
      else { ctx.fillStyle = "white"; ctx.moveTo(X(x), Y(y) - 6); ctx.lineTo(X(x) + 6, Y(y));
             ctx.lineTo(X(x), Y(y) + 6); ctx.lineTo(X(x) - 6, Y(y)); ctx.closePath(); }
      ctx.fill(); ctx.stroke();
    });
    ctx.fillStyle = "#222"; ctx.font = "14px system-ui, sans-serif";
    ctx.fillText(`t = ${g.t[k].toFixed(2)} s   ${g.state[k]}`, 10, 20);
    ctx.fillStyle = S.state[g.state[k]] || "#222"; ctx.fillRect(W - 24, 8, 14, 14);
    frameEl.textContent = `frame ${k + 1} / ${g.t.length} · t = ${g.t[k].toFixed(2)} s · ${g.state[k]}`
      + " · feet: ● stick, ◇ slide";
    frameEl.dataset.frame = String(k);
    window.rtwReport.frame = k;
  }

  function tick(now) {
    if (!anim) return;
    const g = anim.g, n = g.t.length;
    if (playing) {
      // A frame's timestamp can precede the click that started the animation.
      anim.k = Math.floor(Math.max(0, now - anim.t0) / 1000 / anim.dt) % n;
      drawFrame(g, anim.k);
    }
    anim.req = requestAnimationFrame(tick);
  }

  function showSample(i) {
    const id = sid[i];
    const g = gaitOf.get(id);
    const box = document.getElementById("sample-columns");
    let row;
    if (D.detail) {
      row = Object.fromEntries(D.all_columns.map((c) => [c, c === "outcome" ? D.outcomes[D.outcome[i]] : D.columns[c][i]]));
    } else if (g && g.row) {
      row = g.row;
    } else {
      row = Object.fromEntries(Object.keys(D.columns).map((c) => [c, D.columns[c][i]]));
      row.outcome = D.outcomes[D.outcome[i]];
    }
    box.innerHTML = "";
    const h = document.createElement("h3"); h.textContent = `sample ${id}: ${row.outcome}`;
    const t = document.createElement("table"); t.id = "sample-table"; t.dataset.sampleId = String(id);
    Object.entries(row).forEach(([c, v]) => {
      const tr = t.insertRow(); tr.insertCell().textContent = c; tr.insertCell().textContent = fmt(v);
    });
    box.append(h, t);
    if (!D.detail && !(g && g.row)) {
      const p = document.createElement("p"); p.className = "note";
      p.textContent = `A scan of more than ${D.detail_rows.toLocaleString("en")} rows keeps only the plotted `
        + "columns in the page; the others are in samples.parquet.";
      box.appendChild(p);
    }
    if (anim) cancelAnimationFrame(anim.req);
    anim = null;
    window.rtwReport.frame = null;
    frameEl.textContent = ""; delete frameEl.dataset.frame;
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    if (g && g.t.length === 0) {
      noteEl.textContent = `Sample ${id} has no gait to show: ${g.empty}.` + (g.note ? ` Note: ${g.note}` : "");
      return;
    }
    if (!g) {
      noteEl.textContent = `No gait was computed for sample ${id}: the report computes the gaits of the samples `
        + `listed above. Add this one with: python -m rtw report DIR --sample ${id}`;
      return;
    }
    noteEl.textContent = `Sample ${id}'s last ${(g.t[g.t.length - 1] - g.t[0]).toFixed(1)} s, computed by rtw.trace with the `
      + "scan's config and drawn from rtw.draw's geometry, in real time." + (g.note ? ` Note: ${g.note}` : "");
    anim = { g, k: 0, dt: g.t.length > 1 ? (g.t[g.t.length - 1] - g.t[0]) / (g.t.length - 1) : 0.04, t0: performance.now() };
    drawFrame(g, 0);
    anim.req = requestAnimationFrame(tick);
  }
  window.rtwReport.showSample = showSample;
  const onClick = (ev) => { const p = ev.points && ev.points[0]; if (p && p.customdata !== undefined) showSample(p.customdata); };
  gm.on("plotly_click", onClick);
  if (D.gaits.length) showSample(rowOf.get(D.gaits[0].sample_id));

  await paint();
  mark("first-view");
  window.rtwReport.firstViewMs = performance.now();

  // ---- the views further down, each after the browser has painted the last.
  mark("parallel coordinates");
  // ---- parallel coordinates with brushing and a count of the selection.
  const pcCols = [...D.inputs, ...D.outputs.filter((c) => !D.inputs.includes(c))];
  const pcValues = [];
  const dims = pcCols.map((c) => {
    const v = D.columns[c];
    const [lo, hi] = D.ranges[c] || [0, 1];
    const hasNone = D.big ? bytes(D.big.codes[c]).includes(D.big.none) : v.some((x) => x === null);
    const none = lo - 0.1 * ((hi - lo) || 1);
    const values = hasNone ? v.map((x) => (x === null ? none : x)) : v;
    pcValues.push(values);
    const d = { label: label(c), values, range: [hasNone ? none : lo, hi] };
    if (hasNone) {
      const ticks = [0, 1, 2, 3, 4].map((k) => lo + (k * (hi - lo)) / 4);
      d.tickvals = [none, ...ticks];
      d.ticktext = ["none", ...ticks.map((t) => t.toPrecision(3))];
    }
    return d;
  });
  const pc = document.getElementById("parcoords");
  Plotly.newPlot(pc, [{
    type: "parcoords", dimensions: dims,
    line: { color: D.outcome, colorscale: stepped(ocolor), cmin: -0.5, cmax: K - 0.5, showscale: false },
  }], { margin: { l: 70, r: 70, t: 50, b: 30 } }, cfg);
  const countEl = document.getElementById("count");
  if (D.big) {
    countEl.title = `Counted over every sample from its bin (1/${D.big.bins} of each axis): `
      + "a sample counts when its bin meets the brushed range.";
  }
  function brushed() {
    const ranges = pc.data[0].dimensions.map((d) => {
      const r = d.constraintrange;
      if (!r || r.length === 0) return null;
      return Array.isArray(r[0]) ? r : [r];
    });
    const per = new Array(K).fill(0);
    const picked = new Uint8Array(D.n);
    let total = 0;
    if (D.big) {
      total = countCoded(D, pcCols, ranges, per, picked);
    } else for (let i = 0; i < D.n; i++) {
      let ok = true;
      for (let j = 0; j < ranges.length && ok; j++) {
        const r = ranges[j];
        if (!r) continue;
        const v = pcValues[j][i];
        ok = r.some(([a, b]) => v >= a && v <= b);
      }
      if (ok) { total++; per[D.outcome[i]]++; picked[i] = 1; }
    }
    // The gait map shows the brushed samples, the others faded.
    const gmap = document.getElementById("gaitmap");
    if (D.big) {
      if (gmap.data) gmap.redraw(ranges.every((r) => !r) ? null : picked);
    } else if (gmap.data) {
      const all = ranges.every((r) => !r);
      Plotly.restyle(gmap, { selectedpoints: byOutcome.map((m) => (all ? null : m.flatMap((i, p) => (picked[i] ? [p] : [])))) });
    }
    window.rtwReport.selected = total;
    window.rtwReport.selectedPer = Object.fromEntries(D.outcomes.map((o, k) => [o, per[k]]));
    countEl.dataset.selected = String(total);
    countEl.textContent = `${total.toLocaleString("en")} of ${D.n.toLocaleString("en")} samples selected: `
      + D.outcomes.map((o, k) => `${o} ${per[k].toLocaleString("en")}`).join(", ");
  }
  pc.on("plotly_restyle", brushed);
  brushed();

  await paint();
  mark("parallel categories");
  // ---- parallel categories: outcome against binned α, f_n, φ (aggregated in Python).
  const P = D.parcats;
  const ocode = Object.fromEntries(D.outcomes.map((o, k) => [o, k]));
  Plotly.newPlot("parcats", [{
    type: "parcats", counts: P.counts, arrangement: "freeform",
    dimensions: P.dims.map((c, k) => ({
      label: label(c), values: P.values.map((v) => v[k]),
      categoryorder: "array", categoryarray: P.order[k],
    })),
    line: { color: P.values.map((v) => ocode[v[3]]), colorscale: stepped(ocolor), cmin: -0.5, cmax: K - 0.5,
            shape: "hspline" },
  }], { margin: { l: 80, r: 80, t: 30, b: 20 } }, cfg);

  await paint();
  mark("failure clusters");
  // ---- failure clusters in 3-D and the three projections of Fig. S4.
  const C = D.clusters;
  document.getElementById("cluster-note").textContent = D.big
    ? `${D.big.failures.toLocaleString("en")} failures: the 3-D view draws the ${C.index.length.toLocaleString("en")} failures `
      + "among the drawn samples (collapse: filled, stall: open), the projections every failure's density by cluster "
      + `(grey: a failure in no cluster); clusters: ${C.how}.`
    : `${C.index.length.toLocaleString("en")} failures (collapse: filled, stall: open); clusters: ${C.how}.`;
  const ccol = (j) => (j >= 0 ? S.cluster[j % S.cluster.length] : "#999");
  const groups = new Map();
  C.index.forEach((i, k) => { const j = C.cluster[k]; if (!groups.has(j)) groups.set(j, []); groups.get(j).push(i); });
  const cname = (j) => (j >= 0 && C.centres[j] ? `cluster ${j + 1}: ${C.centres[j].name}` : "unassigned");
  const isCollapse = (i) => D.outcomes[D.outcome[i]] === "collapse";
  const keys = [...groups.keys()].sort((a, b) => a - b);
  Plotly.newPlot("clusters3d", [
    ...keys.map((j) => { const m = groups.get(j); return {
      type: "scatter3d", mode: "markers", name: cname(j), customdata: m,
      x: m.map((i) => A[i]), y: m.map((i) => F[i]), z: m.map((i) => PHI[i]),
      marker: { size: 3, color: ccol(j), symbol: m.map((i) => (isCollapse(i) ? "circle" : "circle-open")) },
      text: m.map((i) => sid[i]),
      hovertemplate: "sample %{text}<extra>%{fullData.name}</extra>" }; }),
    { type: "scatter3d", mode: "markers", name: "k-means centres", x: C.centres.map((c) => c.alpha),
      y: C.centres.map((c) => c.fn), z: C.centres.map((c) => c.phi), hoverinfo: "name",
      marker: { size: 7, color: "black", symbol: "diamond" } },
  ], { scene: { xaxis: { title: { text: "α" } }, yaxis: { title: { text: "f_n [Hz]" } }, zaxis: { title: { text: "φ [rad]" } } },
       margin: { l: 0, r: 0, t: 10, b: 0 }, legend: { x: 0, y: 1 } }, cfg);
  document.getElementById("clusters3d").on("plotly_click", onClick);
  const cols = { alpha: A, fn: F, phi: PHI };
  [["alpha", "fn"], ["alpha", "phi"], ["fn", "phi"]].forEach(([cx, cy], p) => {
    if (D.big) {
      // Every failure, per cluster, as a density (the last group: failures without one).
      const P = D.big.clusters, colors = [...Array(P.groups).keys()].map((j) => (j < P.groups - 1 ? ccol(j) : "#999"));
      Plotly.newPlot(`proj${p}`, [{ type: "scatter", mode: "markers", name: "k-means centres", showlegend: false,
        hoverinfo: "name", x: C.centres.map((c) => c[cx]), y: C.centres.map((c) => c[cy]),
        marker: { size: 14, color: "black", symbol: "x" } }],
      { images: imageOn(densityPng(P.grids[p], colors, D.big.bins), axisOf(D.ranges[cx]), axisOf(D.ranges[cy])),
        xaxis: { title: { text: label(cx) }, range: axisOf(D.ranges[cx]) },
        yaxis: { title: { text: label(cy) }, range: axisOf(D.ranges[cy]) },
        margin: { t: 10, r: 10 } }, cfg);
      return;
    }
    Plotly.newPlot(`proj${p}`, [
      ...keys.map((j) => { const m = groups.get(j); return {
        type: scatter(C.index.length), mode: "markers", name: cname(j), customdata: m, showlegend: false,
        x: m.map((i) => cols[cx][i]), y: m.map((i) => cols[cy][i]),
        marker: { size: 5, color: m.map((i) => (isCollapse(i) ? ccol(j) : "rgba(0,0,0,0)")),
                  line: { color: ccol(j), width: 1 } },
        text: m.map((i) => sid[i]),
      hovertemplate: "sample %{text}<extra>%{fullData.name}</extra>" }; }),
      { type: scatter(C.index.length), mode: "markers", name: "k-means centres", showlegend: false, hoverinfo: "name",
        x: C.centres.map((c) => c[cx]), y: C.centres.map((c) => c[cy]),
        marker: { size: 14, color: "black", symbol: "x" } },
    ], { xaxis: { title: { text: label(cx) } }, yaxis: { title: { text: label(cy) } },
         margin: { t: 10, r: 10 } }, cfg);
    document.getElementById(`proj${p}`).on("plotly_click", onClick);
  });

  await paint();
  mark("sensitivity");
  // ---- sensitivity indices and maps, when the directory has them.
  if (D.sensitivity) {
    document.getElementById("sensitivity-section").hidden = false;
    document.getElementById("sensitivity-note").textContent =
      `From ${D.sensitivity.file}: first-order (S1) and total (ST) Sobol indices with their 95 % confidence.`;
    const rows = D.sensitivity.rows;
    [...new Set(rows.map((r) => r.output))].forEach((out, k) => {
      const r = rows.filter((x) => x.output === out);
      const div = document.createElement("div");
      div.id = `sensitivity-${k}`; div.style.width = "420px"; div.style.height = "300px";
      document.getElementById("sensitivity").appendChild(div);
      Plotly.newPlot(div, ["S1", "ST"].map((s) => ({
        type: "bar", name: s, x: r.map((x) => label(x.parameter)), y: r.map((x) => x[s]),
        error_y: { type: "data", array: r.map((x) => x[`${s}_conf`]) } })),
        { title: { text: `output: ${out}` }, barmode: "group", margin: { t: 40, r: 10 } }, cfg);
    });
  }
  showImages(D.images, 700);
}

boot(main);
