// The design page of `python -m rtw report DIR` for a design search's folder
// or an atlas (crates/rtw-py/python/rtw/design_report.py), after boot.js.
// Every number drawn is a column of the search's files; nothing is computed
// here but the cumulative count of simulations and the best value so far.
const PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"];
const UNIT = { slope_range: "slope range [rad]", phi_min: "shallowest stable φ [rad]", speed: "speed [m/s]",
  mfpt: "MFPT [steps]" };
const f4 = (v) => (v === null || v === undefined ? "none" : Number(v).toPrecision(4));

function designText(r, i) {
  return `ρ ${f4(r.rho[i])}, α ${f4(r.alpha[i])}, f_n ${f4(r.fn[i])}, ζ ${f4(r.zeta[i])}<br>`
    + `[${f4(r.phi_lo[i])}, ${f4(r.phi_hi[i])}] rad`;
}

async function main(D) {
  const cfg = { displaylogo: false, responsive: true };
  const colour = (k) => PALETTE[k % PALETTE.length];
  const searches = D.searches;

  // ---- the atlas: every reported design on the same axes.
  const reported = searches.map((s, k) => [s, k]).filter(([s]) => s.reported);
  const atlas = (y, el, title) => Plotly.newPlot(el, reported.map(([s, k]) => {
    const r = s.reported, n = r.rho.length;
    return {
      type: "scatter", mode: "markers", name: s.name, x: r.slope_range, y: r[y],
      text: Array.from({ length: n }, (_, i) => `${s.name} ${i + 1}: ${designText(r, i)}`),
      hovertemplate: "%{text}<extra></extra>",
      marker: { color: colour(k), size: n === 1 ? 14 : 8, symbol: n === 1 ? "star" : "circle" },
    };
  }), { xaxis: { title: { text: UNIT.slope_range } }, yaxis: { title: { text: title } }, margin: { t: 20 } }, cfg);
  const phis = [...new Set(searches.map((s) => s.settings.speed_phi).filter((v) => v !== null && v !== undefined))];
  if (phis.length > 0) {
    await atlas("speed", "atlas-speed", `speed at φ = ${phis.join(", ")} [m/s]`);
  } else {
    // No search here measured a speed: an empty chart would read as "no
    // design moves"; say instead what would measure one.
    const el = document.getElementById("atlas-speed");
    const note = document.createElement("p");
    note.id = "atlas-speed-note";
    note.className = "note";
    note.textContent = "No speed chart: no search here measured a speed (set speed_phi in its config to measure "
      + "each reported design's speed at that slope).";
    el.replaceWith(note);
  }
  await atlas("phi_min", "atlas-phimin", UNIT.phi_min);
  mark("first-view");

  // ---- the intervals: one line per reported design.
  const lines = [], names = [];
  reported.forEach(([s, k]) => {
    const r = s.reported;
    r.rho.forEach((_, i) => {
      const y = `${s.name} ${i + 1}`;
      names.push(y);
      if (r.profile_phi_lo && r.profile_phi_lo[i] !== null) {
        lines.push({ type: "scatter", mode: "lines", x: [r.profile_phi_lo[i], r.profile_phi_hi[i]], y: [y, y],
          line: { color: colour(k), width: 2 }, opacity: 0.5, showlegend: false, hoverinfo: "skip" });
      }
      if (r.phi_lo[i] !== null) {
        const fails = r.checked_failures ? `, ${r.checked_failures[i]} of ${r.checked_slopes[i]} checked slopes failed` : "";
        lines.push({ type: "scatter", mode: "lines+markers", x: [r.phi_lo[i], r.phi_hi[i]], y: [y, y],
          name: s.name, legendgroup: s.name, showlegend: i === 0, line: { color: colour(k), width: 7 },
          text: [0, 1].map(() => `${y}: ${designText(r, i)}${fails}`), hovertemplate: "%{text}<extra></extra>" });
      }
    });
  });
  await Plotly.newPlot("intervals", lines, {
    xaxis: { title: { text: "slope φ [rad]" } }, margin: { t: 20, l: 130 },
    yaxis: { type: "category", categoryorder: "array", categoryarray: names.slice().reverse() },
    height: Math.max(300, 18 * names.length + 120),
  }, cfg);

  // ---- each search's evaluations.
  const box = document.getElementById("searches");
  for (const [k, s] of searches.entries()) {
    const ev = s.evaluations;
    if (!ev) continue;
    const div = document.createElement("div");
    div.className = "plot"; div.style.width = "620px"; div.style.height = "400px";
    box.appendChild(div);
    const n = ev.index.length, obj = s.settings.objectives;
    const spent = []; let total = 0;
    for (let i = 0; i < n; i++) { total += ev.runs[i]; spent.push(total); }
    const ok = [], fell = [];
    for (let i = 0; i < n; i++) (ev.feasible[i] ? ok : fell).push(i);
    const pick = (col, idx) => idx.map((i) => ev[col][i]);
    const hover = (idx) => idx.map((i) => `#${ev.index[i]} ρ ${f4(ev.rho[i])} α ${f4(ev.alpha[i])} f_n ${f4(ev.fn[i])} `
      + `ζ ${f4(ev.zeta[i])}${ev.infeasible[i] ? `<br>fell: ${ev.infeasible[i]}` : ""}`
      + (ev.p_fall[i] !== null ? `<br>learned fall probability ${f4(ev.p_fall[i])}` : ""));
    let traces, layout;
    if (obj.length === 1) {
      const y = obj[0], sign = y === "phi_min" ? -1 : 1;
      const best = []; let b = null;
      for (let i = 0; i < n; i++) {
        const v = ev.feasible[i] ? ev[y][i] : null;
        if (v !== null && (b === null || sign * v > sign * b)) b = v;
        best.push(b);
      }
      const floor = Math.min(...ok.map((i) => ev[y][i]).filter((v) => v !== null), 0);
      traces = [
        { type: "scatter", mode: "markers", name: "evaluated", x: pick("index", ok).map((_, j) => spent[ok[j]]),
          y: pick(y, ok), text: hover(ok), hovertemplate: "%{text}<extra></extra>",
          marker: { color: colour(k), size: 4, opacity: 0.6 } },
        { type: "scatter", mode: "markers", name: "fell (not scored)", x: fell.map((i) => spent[i]),
          y: fell.map(() => floor), text: hover(fell), hovertemplate: "%{text}<extra></extra>",
          marker: { color: "#999", size: 5, symbol: "x" } },
        { type: "scatter", mode: "lines", name: "best so far", x: spent, y: best, line: { color: "#000", width: 1.5 } },
      ];
      layout = { title: { text: `${s.name}: ${y}`, font: { size: 13 } }, xaxis: { title: { text: "simulations spent" } },
        yaxis: { title: { text: UNIT[y] || y } } };
    } else {
      const [a, b] = obj, rep = s.reported;
      traces = [
        { type: "scatter", mode: "markers", name: "evaluated", x: pick(a, ok), y: pick(b, ok), text: hover(ok),
          hovertemplate: "%{text}<extra></extra>", marker: { color: "#bbb", size: 4 } },
      ];
      if (rep) {
        traces.push({ type: "scatter", mode: "markers", name: "front (checked)", x: rep[a], y: rep[b],
          text: rep.rho.map((_, i) => designText(rep, i)), hovertemplate: "%{text}<extra></extra>",
          marker: { color: colour(k), size: 9 } });
      }
      layout = { title: { text: `${s.name}: ${a} against ${b} (${fell.length} of ${n} fell)`, font: { size: 13 } },
        xaxis: { title: { text: UNIT[a] || a } }, yaxis: { title: { text: UNIT[b] || b } } };
    }
    layout.margin = { t: 40 };
    await Plotly.newPlot(div, traces, layout, cfg);
  }

  // ---- the profiles.
  if (D.profiles.length) {
    document.getElementById("profiles-section").hidden = false;
    const pbox = document.getElementById("profiles");
    for (const p of D.profiles) {
      const div = document.createElement("div");
      div.className = "plot"; div.style.width = "620px"; div.style.height = "360px";
      pbox.appendChild(div);
      const outcomes = [...new Set(p.outcome)];
      const traces = outcomes.map((o) => {
        const idx = p.phi.map((_, i) => i).filter((i) => p.outcome[i] === o);
        return { type: "scatter", mode: "markers", name: o, x: idx.map((i) => p.phi[i]),
          y: idx.map((i) => (p.speed[i] === null ? 0 : p.speed[i])), marker: { color: D.style.outcome[o] || "#999", size: 4 },
          hovertemplate: `${o}<br>φ %{x:.4f}<br>speed %{y:.3f}<extra></extra>` };
      });
      const shapes = p.changes.map((c) => ({ type: "line", xref: "x", yref: "paper", x0: c.phi_left, x1: c.phi_left,
        y0: 0, y1: 1, line: { color: "#555", width: 1, dash: "dot" } }));
      const d = p.design;
      await Plotly.newPlot(div, traces, {
        title: { text: `${p.file}: ρ ${f4(d.rho)} α ${f4(d.alpha)} f_n ${f4(d.fn)} ζ ${f4(d.zeta)}`, font: { size: 12 } },
        xaxis: { title: { text: "slope φ [rad]" } }, yaxis: { title: { text: "speed [m/s] (0: no gait)" } },
        shapes, margin: { t: 40 },
      }, cfg);
    }
  }

  showImages(D.images, 640);
}

boot(main);
