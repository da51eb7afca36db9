"""A scan's page (docs/report.md): :func:`scan_of` takes the scan as
rtw-scan's verified reader read it, :func:`pick` chooses what the page shows
and computes the gaits, :func:`render` makes the HTML. ``rtw.report``
(report.py) runs them.

The page is one self-contained file: Plotly.js (a bundle of
only the trace types the page draws, report_assets/plotly-rtw.min.js) and the data
are inlined (gzip, base64; the browser inflates them with its own
DecompressionStream), so it opens offline from disk with no server and no CDN.
It shows the scan's header and summary, parallel coordinates of the inputs
and chosen outputs with brushing, parallel categories of the outcome against
binned inputs, the failure clusters of Fig. S4 in 3-D and in its three 2-D
projections with the k-means centres, the sensitivity indices when the
directory has them, and for a clicked sample all its columns and its gait,
animated.

The gaits are computed here, in Python: each representative sample (the
failure nearest each cluster centre, a few per outcome, and any asked for) is
run again with ``rtw.trace`` under the scan's own stored config, checked
against its row (same outcome) and against the model's geometry
(``rtw.draw.check_geometry``), and turned into world-frame segments with
``rtw.draw`` (rods, strings, ground, feet and their contact modes). The page's
script only draws those segments; it never re-derives the robot.

Only the standard library is imported here at module level, so that
``import rtw`` stays light; numpy (the ``report`` extra:
``pip install 'rtw[report]'``) is needed when a report is made.
"""

from __future__ import annotations

import base64
import html
import json
import math
import tomllib
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Iterable, Sequence

from . import _rtw
from ._progress import Progress
from ._page import ReportError, clean, images, page, style, text_metadata
from ._rtw import FAILURE_LABELS, LABELS, failure_clusters

# The paper's five design inputs (L is fixed by its scan); L joins them when a scan varies it.
INPUTS = ("rho", "alpha", "fn", "zeta", "phi")
DEFAULT_OUTPUTS = ("speed", "f_w", "mu_required")
# Outcomes in rtw-model's order (Label::ALL).
OUTCOMES = LABELS
# Every column of every row goes into the page up to this many rows (a click
# shows them all); above it, only the plotted columns do, and all columns only
# for the samples with a gait (the page says so).
DETAIL_ROWS = 20_000
# The views draw at most PLOT_ROWS samples: above, a seeded random subset of
# that many (the same in every view, and said on the page), while the counts
# (summary, brushing) are of every row. A report takes at most MAX_ROWS rows
# (docs/report.md gives the measured sizes and times).
PLOT_ROWS = 20_000
MAX_ROWS = 1_000_000
# A gait is shown over the last TRACE_WINDOW seconds of its run (the settled
# gait of a stable run, the fall or the stop of a failed one), one frame every
# FRAME_DT seconds of simulated time, played in real time.
TRACE_WINDOW = 8.0
FRAME_DT = 0.04
PER_OUTCOME = 2


@dataclass(frozen=True)
class Scan:
    """A scan's folder as rtw-scan's verified reader gave it (:func:`scan_of`):
    the folder the page's images and indices come from (`base`), the rows,
    the files read, the summary.json beside them (parsed) and the
    assignments file (its path and pairs), when they are the scan's own."""

    base: Path
    table: Any
    files: list[Path]
    summary: dict | None
    found: tuple[Path, list[tuple[int, int]]] | None
    meta: dict[str, str]
    config_text: str
    config: dict[str, Any]


def scan_of(base: Path, table: Any, files: list[Path], summary_text: str | None, found: Any) -> Scan:
    """The scan `_rtw.read_scan_folder` read (rtw-scan's verified reader: the
    files' hashes, the rows' values, the ids once each in order, every shard
    of an unmerged set, and beside the scan its summary.json and assignments
    file only when they are its own), refused when it has no rows or more
    than a report takes."""
    meta = text_metadata(table.schema.metadata)
    n = table.num_rows
    if n == 0:
        raise ReportError(f"DIR: {files[0]} has no rows")
    if n > MAX_ROWS:
        raise ReportError(f"DIR: {n:,} rows; a report plots at most {MAX_ROWS:,} (docs/report.md): "
                          "report a shard's part or a smaller scan")
    config_text = meta["rtw.config"]
    summary = json.loads(summary_text) if summary_text is not None else None
    return Scan(base, table, files, summary, found, meta, config_text, tomllib.loads(config_text))


@dataclass(frozen=True)
class Shown:
    """What the page shows of a scan (:func:`pick`): its `data` (the JSON
    the page's script draws) and the outcome counts of every row."""

    data: dict[str, Any]
    counts: Counter


def _representatives(rows: dict[str, list], clusters: dict[int, int] | None, centres: list[dict],
                     per_outcome: int, asked: Iterable[int]) -> list[tuple[int, str]]:
    """(row index, why) of the samples whose gait the page animates: the
    failure nearest each cluster centre, then per outcome the `per_outcome`
    samples nearest the outcome's mean in standardized (α, f_n, φ), then the
    samples asked for by id. A run that moved (t_end > 0) comes before one
    that ended at once (a star that cannot stand has nothing to animate)."""
    import numpy as np

    n = len(rows["sample_id"])
    pts = np.array([rows[c] for c in ("alpha", "fn", "phi")], dtype=float).T
    sd = pts.std(axis=0) if n > 1 else np.ones(3)
    sd[sd <= 0] = 1.0
    z = pts / sd
    chosen: list[tuple[int, str]] = []
    taken: set[int] = set()
    index = {sid: i for i, sid in enumerate(rows["sample_id"])}
    still = [not (t or 0) > 0 for t in rows["t_end"]]
    if clusters:
        for j, c in enumerate(centres):
            members = [index[s] for s, k in clusters.items() if k == j and s in index]
            if not members:
                continue
            cz = np.array([c["alpha"], c["fn"], c["phi"]]) / sd
            best = min(members, key=lambda i: (still[i], float(((z[i] - cz) ** 2).sum()), i))
            chosen.append((best, f"nearest cluster {j + 1}'s centre ({c.get('name', '')})"))
            taken.add(best)
    outcome = rows["outcome"]
    for o in OUTCOMES:
        members = [i for i in range(n) if outcome[i] == o]
        if not members:
            continue
        m = z[members].mean(axis=0)
        members.sort(key=lambda i: (still[i], float(((z[i] - m) ** 2).sum()), i))
        picked = [i for i in members if i not in taken][:per_outcome]
        for rank, i in enumerate(picked):
            chosen.append((i, f"a typical {o} ({rank + 1} of {len(picked)})"))
            taken.add(i)
    for sid in asked:
        if sid not in index:
            raise ReportError(f"--sample: sample_id {sid} is not in the scan (ids {rows['sample_id'][0]} "
                              f"… {rows['sample_id'][-1]})")
        if index[sid] not in taken:
            chosen.append((index[sid], "asked for"))
            taken.add(index[sid])
    return chosen


def _gait(row: dict[str, Any], config_text: str, options: dict) -> dict[str, Any]:
    """One sample's gait as the page draws it: per frame, world-frame segments
    of the rods and strings, the feet on the ground with their contact mode,
    the contact state and the view's centre, from rtw.trace and rtw.draw."""
    import numpy as np

    from . import trace as run_trace
    from .draw import MINUS, PLUS, STATE_NAMES, STRINGS, Geometry, Trace, check_geometry, slope_axes, stance_tips, star_points

    inputs = [row[c] for c in ("length", "rho", "alpha", "fn", "zeta", "phi")]
    table = run_trace(*inputs, config=config_text, dt=FRAME_DT)
    ran = json.loads(table.schema.metadata[b"rtw.outcome"])
    note = None
    if ran["outcome"] != row["outcome"]:
        note = (f"this trace's run ended as {ran['outcome']}, the scan's row says {row['outcome']}: "
                "the scan was not made with this rtw version's model")
    if table.num_rows == 0:
        # A star that cannot stand in its initial shape ends before its first sample.
        return {"sample_id": int(row["sample_id"]), "outcome": ran["outcome"], "t": [], "note": note,
                "empty": f"the run ended at t = 0, before its first trace sample ({ran.get('message') or ran['outcome']})"}
    design = Geometry.from_params(row["length"], row["alpha"], row["phi"], options, k=row["k"])
    tr = Trace(table, design)
    check_geometry(tr)
    # Frames at even times (the trace also holds the event instants), each the
    # sample nearest its time, as rtw.animate draws them.
    start = max(float(tr.t[0]), float(tr.t[-1]) - TRACE_WINDOW)
    keep = tr.nearest(start + FRAME_DT * np.arange(int((float(tr.t[-1]) - start) / FRAME_DT + 1e-9) + 1))
    d, to_world = design, slope_axes(design.phi)
    tips, conns = (p @ to_world for p in star_points(tr.x[:, keep], tr.y[:, keep], tr.theta[:, keep],
                                                     d.length, d.r))  # [spoke, sample, xy]
    rods = np.concatenate([tips[PLUS], tips[MINUS]], axis=-1).transpose(1, 0, 2)  # [sample, rod, x0 y0 x1 y1]
    strings = np.concatenate([conns[STRINGS[:, 0]], conns[STRINGS[:, 1]]], axis=-1).transpose(1, 0, 2)  # [sample, string, 4]
    code = tr.contact[:, keep]
    feet = stance_tips(tips[PLUS], tips[MINUS], code).transpose(1, 0, 2)  # [sample, rod, xy]
    hub = np.stack([tr.x[:, keep].mean(axis=0), np.zeros(len(keep))], axis=-1) @ to_world
    centre = hub + np.array([0.0, 0.45 * d.length])
    r6 = lambda a: np.round(a, 5).tolist()  # noqa: E731 (0.01 mm: below a pixel)
    return {
        "sample_id": int(row["sample_id"]),
        "outcome": ran["outcome"],
        "note": note,
        "t": r6(tr.t[keep]),
        "rods": r6(rods),
        "strings": r6(strings),
        "feet": r6(feet),
        "mode": np.abs(code).T.tolist(),  # [sample, rod]: 0 free, 1 stick, 2 slide
        "state": [STATE_NAMES[s] for s in tr.state[keep]],
        "centre": r6(centre),
        "ground": r6(to_world[0]),  # the slope's downhill direction in the world
        "normal": r6(to_world[1]),
        "length": d.length,
        "window": 2.2 * d.length,
    }


def _bins(values: Any, lo: float, hi: float, n: int = 4) -> tuple[list[str], list[str]]:
    """Equal-width bins of [lo, hi]: each value's label 'a–b', and the labels
    in order. `values`: a list, or a column (pyarrow or numpy) of numbers."""
    import numpy as np

    w = (hi - lo) / n if hi > lo else 1.0
    edges = [lo + w * k for k in range(n + 1)]
    labels = [f"{edges[k]:.3g}–{edges[k + 1]:.3g}" for k in range(n)]
    v = np.asarray(values, dtype=float)
    # As int((v - lo) / w) clamped to [0, n - 1]: truncation and floor differ
    # only below 0, which the clamp sends to 0 either way.
    k = np.clip(np.floor((v - lo) / w), 0, n - 1).astype(int)
    return [labels[i] for i in k.tolist()], labels


def _big(table: Any, plotted: list[str], asked: list[int], seed: int) -> tuple[dict[str, list], Counter, dict]:
    """A scan of more than PLOT_ROWS rows, as rtw-scan aggregates it
    (`_rtw.scan_views`): the rows the one-mark-per-row views draw (its
    stratified sample, with the samples asked for), as lists; the outcome
    counts of every row; and the views, their `outcome` as a numpy array."""
    import numpy as np

    view = _rtw.scan_views(table, [c for c in plotted if c != "sample_id"], "alpha", "fn", PLOT_ROWS, seed)
    labels = view["labels"]
    view["outcome"] = np.frombuffer(view["outcome"], np.uint8)
    per = np.bincount(view["outcome"], minlength=len(labels))
    counts = Counter({labels[k]: int(c) for k, c in enumerate(per) if c})
    ids = table["sample_id"].to_numpy()
    # The ids are in order (rtw-scan's reader checks it); one not in the scan
    # is refused by _representatives, which names the scan's ids.
    at = np.searchsorted(ids, np.asarray(asked, dtype=np.int64))
    asked_rows = [int(i) for i, sid in zip(at, asked) if i < len(ids) and ids[i] == sid]
    picked = np.union1d(np.asarray(view["sample"], dtype=np.int64), np.asarray(asked_rows, dtype=np.int64))
    return table.take(picked).to_pydict(), counts, view


def _shown(values: list) -> list:
    """A drawn column of a large scan, to 7 significant digits: the page shows
    6 (and brushing counts from the codes), and the page is a third smaller."""
    return [v if not isinstance(v, float) else (float(f"{v:.7g}") if math.isfinite(v) else None) for v in values]


def _big_clusters(view: dict, table: Any, assign: dict[int, int], k: int) -> dict[str, Any]:
    """The failure projections of a large scan, per cluster, in rtw-scan
    (`_rtw.density_grid`): every failure's cluster (`k` for one without),
    counted on the grids of (α, f_n), (α, φ) and (f_n, φ)."""
    import numpy as np

    ids = table["sample_id"].to_numpy()
    labels = view["labels"]
    group = np.full(len(ids), 255, dtype=np.uint8)
    group[np.isin(view["outcome"], [labels.index(f) for f in FAILURE_LABELS])] = k
    if assign:
        a_ids = np.fromiter(assign.keys(), dtype=np.int64, count=len(assign))
        a_k = np.fromiter(assign.values(), dtype=np.int64, count=len(assign))
        at = np.minimum(np.searchsorted(ids, a_ids), len(ids) - 1)
        mine = (ids[at] == a_ids) & (a_k >= 0) & (a_k < k)
        group[at[mine]] = a_k[mine]
    codes = {c: view["columns"][c][1] for c in ("alpha", "fn", "phi")}
    pairs = [("alpha", "fn"), ("alpha", "phi"), ("fn", "phi")]
    return {"groups": k + 1,
            "grids": [_rtw.density_grid(group.tobytes(), k + 1, codes[x], codes[y]) for x, y in pairs]}


def _big_page(view: dict, names: list[str], shown: int) -> dict[str, Any]:
    """What the page gets of `view` (`_big`): every row's outcome (its index
    in `names`) and plotted columns coded a byte each, base64; the columns'
    ranges are the page's `ranges`; the gait map's densities per outcome."""
    import numpy as np

    labels = view["labels"]
    to_name = np.full(256, 255, dtype=np.uint8)
    for k, label in enumerate(labels):
        if label in names:
            to_name[k] = names.index(label)
    b64 = lambda b: base64.b64encode(b).decode()  # noqa: E731
    return {
        "rows": shown,
        "bins": view["code_bins"],
        "none": view["code_none"],
        "outcome": b64(to_name[view["outcome"]].tobytes()),
        "codes": {c: b64(codes) for c, (_, codes) in view["columns"].items()},
        "density": {"x": "alpha", "y": "fn", "grids": [view["density"][labels.index(o)] for o in names]},
    }


def _sensitivity(directory: Path, meta: dict[str, str], rows: int) -> dict | None:
    """Sensitivity indices (indices.parquet: output, parameter, S1, S1_conf,
    ST, ST_conf) in DIR or DIR/sensitivity, when there: read by rtw-scan's
    verified reader, which refuses indices not computed from this scan
    (`meta`, its metadata, and `rows`, its row count)."""
    if not directory.is_dir():
        return None
    for f in (directory / "indices.parquet", directory / "sensitivity" / "indices.parquet"):
        if f.is_file():
            t = _rtw.read_indices(f, meta, rows)
            need = ["output", "parameter", "S1", "S1_conf", "ST", "ST_conf"]
            return {"file": f.name, "rows": clean(t.select(need).to_pylist())}
    return None


def _header(meta: dict[str, str], summary: dict | None, n: int, counts: Counter, files: Sequence[Path],
            version: str) -> str:
    """The header's HTML: config, variant, seed, size, versions, and the summary table."""
    e = html.escape
    config = meta["rtw.config"]
    name = tomllib.loads(config).get("name", "?")
    items = [("scan", name), ("file", ", ".join(str(f) for f in files)), ("samples", f"{n:,}"),
             ("seed", meta.get("rtw.seed", "?")), ("model variant", meta.get("rtw.variant", "?")),
             ("computed by rtw", meta.get("rtw.version", "?")), ("report made by rtw", version),
             ("config hash", meta.get("rtw.config_hash", "?"))]
    dl = "".join(f"<tr><th>{e(k)}</th><td>{e(str(v))}</td></tr>" for k, v in items)
    paper = bool(summary and summary.get("paper_scan"))
    rows = []
    if summary:
        for o in [*summary["outcomes"], summary.get("stable"), summary.get("failed")]:
            if not o:
                continue
            lo, hi = o.get("ci95") or (None, None)
            ci = f"{lo:.1f}–{hi:.1f}" if lo is not None else ""
            pp = o.get("paper_percent")
            cells = [o["outcome"], f"{o['count']:,}", f"{o['percent']:.1f}", ci]
            if paper:
                cells.append("" if pp is None else f"{pp:.1f}")
            rows.append(cells)
        head = ["outcome", "count", "%", "95 % CI (%)"] + (["paper %"] if paper else [])
        src = "summary.json (rtw-scan summary)" + ("; paper %: the percentages the paper reports" if paper else "")
    else:
        head = ["outcome", "count", "%"]
        rows = [[o, f"{c:,}", f"{100 * c / max(n, 1):.1f}"] for o, c in counts.most_common()]
        src = "counted from the rows (the directory has no summary.json)"
    table = ("<table class='summary'><thead><tr>" + "".join(f"<th>{e(h)}</th>" for h in head) + "</tr></thead><tbody>"
             + "".join("<tr>" + "".join(f"<td>{e(c)}</td>" for c in r) + "</tr>" for r in rows)
             + f"</tbody></table><p class='note'>Source: {e(src)}.</p>")
    if "rtw.refine" in meta:
        # rtw-scan refine's combined file: its rows are not draws from the box.
        table += ("<p class='note'>Refined scan (rtw-scan refine): its added samples crowd where the labels "
                  "change, so these shares are the refined sample's, not the box's.</p>")
    return (f"<h1>rtw scan report: {e(name)}</h1><div class='head'><table class='meta'>{dl}</table>{table}</div>"
            f"<details><summary>config (as stored in the scan file, rtw.config)</summary><pre>{e(config)}</pre></details>")


def pick(scan: Scan, outputs: list[str], per_outcome: int, samples: list[int], tell: Progress) -> Shown:
    """What the page shows of `scan`: the inputs and `outputs` on the
    parallel coordinates, every row or, above PLOT_ROWS, rtw-scan's
    aggregates and stratified sample, the parallel categories, the failure
    clusters, the gaits of the representative samples (`per_outcome` per
    outcome, and `samples`; each run again, counted by `tell`, the progress
    bar), the sensitivity indices and the images."""
    table = scan.table
    n = table.num_rows
    inputs, plotted = _plotted(table, outputs)
    big = n > PLOT_ROWS
    if big:
        # Too many rows to send one by one: rtw-scan aggregates them (every
        # plotted column coded a byte per row, per-outcome densities of the
        # gait map) and picks the rows the one-mark-per-row views draw.
        rows, counts, big_view = _big(table, plotted, samples, int(scan.meta.get("rtw.seed", "0")))
    else:
        rows = table.to_pydict()
        counts = Counter(rows["outcome"])
        big_view = None
    # "clusters" is null when there are fewer failures than the config's k.
    centres = ((scan.summary or {}).get("clusters") or {}).get("clusters") or []
    failed = [i for i, o in enumerate(rows["outcome"]) if o in FAILURE_LABELS]
    assign, how = _assignments(scan, centres, failed)

    detail = n <= DETAIL_ROWS
    names = [o for o in OUTCOMES if counts.get(o)] + sorted(o for o in counts if o not in OUTCOMES)
    code = {o: k for k, o in enumerate(names)}
    data: dict[str, Any] = {
        "n": n,
        "inputs": inputs,
        "outputs": outputs,
        "outcomes": names,
        "outcome": [code[o] for o in rows["outcome"]],
        "columns": {c: (_shown(rows[c]) if big else clean(rows[c]))
                    for c in (table.column_names if detail else plotted) if c != "outcome"},
        "all_columns": table.column_names,
        "detail": detail,
        "detail_rows": DETAIL_ROWS,
        "style": style(),
        "ranges": ({c: r for c, (r, _) in big_view["columns"].items() if r is not None} if big else
                   {c: clean([min(v for v in rows[c] if v is not None), max(v for v in rows[c] if v is not None)])
                    for c in plotted if any(v is not None for v in rows[c])}),
    }
    if big:
        data["big"] = _big_page(big_view, names, len(rows["sample_id"]))
        data["big"]["clusters"] = _big_clusters(big_view, table, assign, len(centres))
        data["big"]["failures"] = sum(counts.get(f, 0) for f in FAILURE_LABELS)
    data["parcats"] = _parcats(scan, rows, big_view, data["ranges"], names)
    data["clusters"] = {"centres": clean(centres), "how": how,
                        "index": [i for i in failed], "cluster": [assign.get(rows["sample_id"][i], -1) for i in failed]}
    picks = _representatives(rows, assign, centres, per_outcome, samples)
    with tell as count:
        data["gaits"] = _gaits(scan, rows, picks, detail, count)
    data["sensitivity"] = _sensitivity(scan.base, scan.meta, n)
    # The maps in DIR (robustness maps, figures), up to 2 MB each.
    data["images"] = images(scan.base, ("png",), 2_000_000)[0]
    return Shown(data, counts)


def _plotted(table: Any, outputs: list[str]) -> tuple[list[str], list[str]]:
    """The inputs on the parallel coordinates (L only when the scan varies
    it), and every plotted column: ``sample_id``, the inputs, then
    `outputs`, each of which must be a numeric column of the scan."""
    import pyarrow as pa

    inputs = [c for c in ("length", *INPUTS) if c != "length" or len(set(table["length"].to_pylist())) > 1]
    for c in outputs:
        numeric = c in table.column_names and (pa.types.is_integer(table.schema.field(c).type)
                                               or pa.types.is_floating(table.schema.field(c).type))
        if not numeric:
            raise ReportError(f"outputs: {c!r} is not a numeric column of the scan (docs/data-dictionary.md)")
    return inputs, ["sample_id", *inputs, *[c for c in outputs if c not in inputs]]


def _assignments(scan: Scan, centres: list[dict], failed: list[int]) -> tuple[dict[int, int], str]:
    """Each failure's cluster (sample id → cluster index) and where it comes
    from: the assignments file beside the scan, else rtw-scan's clustering
    of the scan's one file when summary.json has centres, else none."""
    if scan.found:
        return dict(scan.found[1]), f"from {scan.found[0].name} (rtw-scan cluster --assignments)"
    if centres and failed and len(scan.files) == 1:
        # rtw-scan's own clustering of the file (the config's k, seed and
        # restarts), the assignments `rtw-scan cluster --assignments` writes.
        return (dict(failure_clusters(scan.files[0]) or []),
                "rtw-scan's clustering of the failures (as `rtw-scan cluster --assignments` writes it)")
    return {}, "no clusters in summary.json"


def _parcats(scan: Scan, rows: dict[str, list], big_view: dict | None, ranges: dict[str, Any],
             names: list[str]) -> dict[str, Any]:
    """The parallel categories: the outcome against the binned inputs that
    matter most (Fig. S4's three), each binned over the config's box (else
    its range in the rows), counted over every row (the table's columns when
    the rows are not all in `rows`, a large scan's)."""
    box = scan.config.get("params", {})

    def span(c):
        u = box.get(c, {}).get("uniform") if isinstance(box.get(c), dict) else None
        return u if u else ranges[c]

    every = rows
    if big_view is not None:
        import numpy as np

        every = {c: scan.table[c] for c in ("alpha", "fn", "phi")}
        every["outcome"] = np.array(big_view["labels"], dtype=object)[big_view["outcome"]]
    binned = {c: _bins(every[c], *span(c)) for c in ("alpha", "fn", "phi")}
    combos = Counter(zip(*(binned[c][0] for c in ("alpha", "fn", "phi")), every["outcome"]))
    return {"dims": ["alpha", "fn", "phi", "outcome"], "order": [binned[c][1] for c in binned] + [names],
            "values": [list(k) for k in combos], "counts": list(combos.values())}


def _gaits(scan: Scan, rows: dict[str, list], picks: list[tuple[int, str]], detail: bool,
           count: Callable[[int, int], object] | None) -> list[dict[str, Any]]:
    """The gaits of the rows `picks` (row index, why), each run under the
    scan's own stored config (its text, as rtw.trace takes it), counted by
    `count`; each with its row when the page does not carry every column."""
    gaits = []
    options = scan.config.get("simulation", {})
    for k, (i, why) in enumerate(picks):
        if count:
            count(k, len(picks))
        row = {c: rows[c][i] for c in scan.table.column_names}
        g = _gait(row, scan.config_text, options)
        g["why"] = why
        if not detail:
            g["row"] = clean(row)
        gaits.append(g)
    if count:
        count(len(picks), len(picks))
    return gaits


def render(scan: Scan, shown: Shown, plotly_js: str) -> str:
    """The scan's page: its header (config, versions, the summary table)
    and what :func:`pick` chose, with the Plotly.js bundle `plotly_js`."""
    from . import __version__

    header = _header(scan.meta, scan.summary, scan.table.num_rows, shown.counts, scan.files, __version__)
    return page("report", f"rtw report: {scan.config.get('name', '?')}", header, shown.data, plotly_js)
