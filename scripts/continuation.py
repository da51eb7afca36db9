"""Continuation diagrams from `rtw-scan continuation` output: the limit
cycles' branches over a parameter, stable and unstable, with their Floquet
multipliers.

Run through scripts/continuation.sh. Nothing is recomputed here: every
number drawn is read from the files rtw-scan wrote.

    python scripts/continuation.py diagram results/continuation/phi-fig7a.parquet \
        [--sweep results/bifurcation/phi-fig7a.parquet] [--out X.png] [--title TEXT]
  top:    ω of the new stance rod at the section, per branch point and orbit
          step: stable solid, unstable dashed; bifurcations marked; with
          --sweep, the attractor the robot settles in at each value of a
          `rtw-scan bifurcation` sweep as grey dots (the recorded steps);
  bottom: the largest Floquet multiplier modulus, with |μ| = 1.

    python scripts/continuation.py plane results/continuation/phi-fn.parquet \
        results/continuation/plane/samples.parquet [--out X.png] [--check]
  the curves of FILE.curve.parquet in the (param, param2) plane over the
  brute-force scan's grid (`rtw-scan run configs/continuation-plane.toml`),
  each grid point marked by the gait the robot settled in and its period;
  prints, per column of the grid, every φ where the curves cross it (a curve
  that folds in param2 crosses a column more than once; the period-1 walk's
  stability flips at each crossing) and where the scan's runs settle on a
  stable period-1 or period-2 walk, and with --check fails unless they agree
  to the grid's resolution: no stable period-1 walk where continuation has it
  unstable (past a crossing on a curve that stopped unresolved nearby, not
  checked, and said so); a period-2 walk where the period-1 walk is stable is
  a coexisting attractor, reported; in the one-parameter diagram's own column
  one of the two walks is seen between the band where both are stable and the
  doubling (check_column).
  Each figure's title names the model of its data (rtw.variant); the
  files drawn together must be at one model.
"""

from __future__ import annotations

import argparse
import json
import sys
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from rtwscripts import DPI, model  # noqa: E402

SYMBOL = {"phi": "φ [rad]", "length": "L [m]", "rho": "ρ [kg/m]", "alpha": "α", "fn": "f_n [Hz]",
          "zeta": "ζ"}
KIND_STYLE = {"period_doubling": ("o", "#d62728", "period doubling"),
              "fold": ("s", "#1f77b4", "fold"),
              "branch_point": ("^", "#2ca02c", "branch point"),
              "neimark_sacker": ("D", "#9467bd", "Neimark–Sacker")}
PERIOD_COLOR = {1: "#000000", 2: "#ff7f0e", 4: "#8c564b"}


def companion(points: Path, what: str) -> Path:
    return points.with_name(f"{points.stem}.{what}.parquet")


def model_of(data: Path) -> str:
    """The model a file was made at: the part of its `rtw.variant` before the
    run's integrator settings (scripts/check_default_model.py's `model`), so
    that a figure's title names the model of the data it draws and cannot
    drift from it."""
    meta = pq.read_metadata(data).metadata or {}
    variant = meta.get(b"rtw.variant")
    if variant is None:
        sys.exit(f"continuation: {data} has no rtw.variant: its model cannot be named")
    return model(variant.decode())


def titled(fig, title: str, data: Path, width: int) -> str:
    """Sets the figure's title, its first line `title` and then the model of
    `data`; returns the whole title, which `save` also writes into the PNG's
    Title text chunk (read back by scripts/check_default_model.py)."""
    full = title + "\n" + "\n".join(textwrap.wrap(f"model: {model_of(data)}", width))
    fig.suptitle(full, fontsize=9)
    return full


def save(fig, out: Path, title: str) -> None:
    fig.savefig(out, dpi=DPI, metadata={"Title": title.replace("\n", " ")})
    plt.close(fig)


def runs(stable: np.ndarray) -> list[slice]:
    """Index ranges of constant stability, each extended by one point into
    the next so that the drawn line has no gap where stability changes."""
    out, start = [], 0
    for i in range(1, len(stable) + 1):
        if i == len(stable) or stable[i] != stable[start]:
            out.append(slice(start, min(i + 1, len(stable))))
            start = i
    return out


def draw_branches(ax, pts: pl.DataFrame, y: str) -> None:
    for (branch, k), g in pts.sort("branch", "k", "index").group_by(["branch", "k"], maintain_order=True):
        period = int(g["period"][0])
        v, q, st = g["value"].to_numpy(), g[y].to_numpy(), g["stable"].to_numpy()
        for s in runs(st):
            ax.plot(v[s], q[s], color=PERIOD_COLOR.get(period, "#7f7f7f"), lw=1.6,
                    ls="-" if st[s.start] else "--", zorder=3)


def diagram(points: Path, out: Path, sweep: Path | None, title: str | None) -> Path:
    pts = pl.read_parquet(points)
    special = pl.read_parquet(companion(points, "special"))
    param = pts["param"][0]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 7), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 1.4]})
    if sweep is not None:
        # The sweep's attractor is drawn as the same walk's: it must be at the
        # same model, or the grey dots would compare two models.
        if model_of(sweep) != model_of(points):
            sys.exit(f"continuation: {sweep} is at model {model_of(sweep)}, {points} at {model_of(points)}")
        steps = pl.read_parquet(sweep.with_name(sweep.stem + ".steps.parquet"))
        top.scatter(steps["value"], steps["omega"], s=2, color="#b0b0b0", zorder=1, lw=0,
                    label="attractor (rtw-scan bifurcation)")
    draw_branches(top, pts, "omega")
    draw_branches(bottom, pts.filter(pl.col("k") == 0), "floquet_max")
    handles = [Line2D([], [], color="k", lw=1.6, label="period 1, stable"),
               Line2D([], [], color="k", lw=1.6, ls="--", label="period 1, unstable"),
               Line2D([], [], color=PERIOD_COLOR[2], lw=1.6, label="period 2, stable"),
               Line2D([], [], color=PERIOD_COLOR[2], lw=1.6, ls="--", label="period 2, unstable")]
    for kind, (marker, color, name) in KIND_STYLE.items():
        at = special.filter(pl.col("kind").cast(str) == kind)
        if at.is_empty():
            continue
        for ax, ycol in ((top, "omega"), (bottom, "floquet_max")):
            ax.scatter(at["value"], at[ycol], marker=marker, s=46, facecolor="white", edgecolor=color,
                       linewidths=1.6, zorder=5)
        handles.append(Line2D([], [], marker=marker, ls="", markerfacecolor="white", markeredgecolor=color,
                              label=f"{name} ({', '.join(f'{v:.4f}' for v in at['value'])})"))
    if sweep is not None:
        handles.append(Line2D([], [], marker="o", ls="", color="#b0b0b0", markersize=3,
                              label="attractor from a run (rtw-scan bifurcation)"))
    top.set_ylabel("post-impact ω of the new stance rod [rad/s]")
    top.legend(handles=handles, fontsize=8, loc="best")
    bottom.axhline(1.0, color="#999999", lw=0.8)
    bottom.set_ylabel("max |μ|")
    bottom.set_xlabel(SYMBOL.get(param, param))
    meta = pq.read_metadata(points).metadata or {}
    wall = meta.get(b"rtw.wall_time_s", b"?").decode()
    full = titled(fig, title or f"continuation in {param}", points, 110)
    fig.text(0.01, 0.005, f"rtw-scan continuation; {wall} s; variant {meta.get(b'rtw.variant', b'?').decode()}",
             fontsize=5, color="#666666")
    fig.tight_layout(rect=(0, 0.015, 1, 1))
    save(fig, out, full)
    return out


def scan_grid(samples: Path, param: str, param2: str) -> pl.DataFrame:
    """The brute-force scan: one row per grid point, with its gait class:
    `walk1` (a period-1 walk with a stable solved cycle), `walk2` (period 2),
    or the outcome and period otherwise."""
    d = pl.read_parquet(samples).select(param, param2, "outcome", "period", "floquet_max")
    return d.with_columns(
        pl.when((pl.col("outcome").cast(str) == "walk") & pl.col("period").is_in([1, 2])
                & (pl.col("floquet_max") < 1))
        .then(pl.format("walk{}", pl.col("period")))
        .otherwise(pl.format("{}{}", pl.col("outcome").cast(str), pl.col("period")))
        .alias("cls"))


def crossings(curve: pl.DataFrame, col: float) -> list[tuple[float, bool]]:
    """Every φ where a curve of the period-1 walk's bifurcations (period
    doubling or fold, continued from the one-parameter branch) crosses the
    column param2 = col, in order, each with whether it is *open*: on a curve
    whose continuation stopped unresolved ("no continuation": the orbit
    changed its mode sequence, or the corrector failed) with that end within
    a column of col, so that past it the boundary is not known. A curve that
    folds in param2 crosses a column more than once; the two directions of
    one curve share their first point, counted once."""
    out: list[tuple[float, bool]] = []
    for _, g in curve.sort("curve", "index").group_by("curve", maintain_order=True):
        v, w = g["value"].to_numpy(), g["value2"].to_numpy()
        unresolved = str(g["end"][-1]).endswith("no_continuation")
        for i in range(len(v) - 1):
            a, b = w[i] - col, w[i + 1] - col
            # Half-open segments, so that a vertex on the column counts once.
            if (a < 0 <= b) or (b < 0 <= a):
                x = float(v[i] + a / (a - b) * (v[i + 1] - v[i]))
                if all(abs(x - y) > 1e-9 for y, _ in out):
                    out.append((x, unresolved and abs(w[-1] - col) <= OPEN_REACH[0]))
    return sorted(out)


# How far in param2 an unresolved curve end leaves the boundary open: one
# column of the brute-force grid (set by plane_rows before the crossings).
OPEN_REACH = [0.0]


def coexistence(points: Path, param2: str) -> tuple[float, float, float] | None:
    """The one-parameter diagram's subcritical doubling: (its value of
    param2, the period doubling's φ, the far edge of the band before it where
    the period-2 walk born there is stable too), or None when there is no
    such band (a supercritical doubling: the period-2 branch does not reach
    back, stable, over the side where the period-1 walk is stable). The band
    ends where the period-2 branch loses stability on its way back, at the
    latest at its fold. Inside it both walks are attractors, and a run from
    the standing start may settle on either."""
    pts = pl.read_parquet(points)
    special = pl.read_parquet(companion(points, "special"))
    pd = special.filter(pl.col("kind").cast(str) == "period_doubling")
    if pd.is_empty():
        return None
    phi_pd, branch = float(pd["value"][0]), int(pd["branch"][0])
    one = pts.filter((pl.col("branch") == branch) & pl.col("stable"))
    if one.is_empty():
        return None
    side = np.sign(float(one["value"].mean()) - phi_pd)
    stable_two = pts.filter((pl.col("period") == 2) & pl.col("stable"))["value"].to_numpy()
    reach = stable_two[(stable_two - phi_pd) * side > 0]
    if reach.size == 0:
        return None
    edge = float(reach[np.argmax(np.abs(reach - phi_pd))])
    # The diagram's own value of the second input (rtw.params names f_n what
    # the command line calls fn).
    params = json.loads((pq.read_metadata(points).metadata or {}).get(b"rtw.params", b"{}"))
    return float(params.get({"fn": "f_n"}.get(param2, param2), float("nan"))), phi_pd, edge


def ranges(v: np.ndarray, mask: list[bool], step: float) -> str:
    """The grid values where mask holds, as runs of consecutive points."""
    out, start = [], None
    for i, m in enumerate([*mask, False]):
        if m and start is None:
            start = i
        elif not m and start is not None:
            out.append(f"{v[start]:.3f}" if i - 1 == start else f"{v[start]:.3f}–{v[i - 1]:.3f}")
            start = None
    return ", ".join(out) or "none"


def check_column(v: np.ndarray, cls: list[str], xs: list[tuple[float, bool]], step: float,
                 band: tuple[float, float] | None) -> tuple[list[str], list[str]]:
    """What in one column of the scan disagrees with the continuation, and
    what the continuation leaves open there.

    The period-1 walk is stable below the column's first crossing (the
    branch's low end is a change of mode sequence, not of stability) and each
    crossing flips its stability (a multiplier through −1 or +1). So a stable
    period-1 walk of the scan must lie where continuation has the period-1
    walk stable, or within a grid step of a crossing; past an open crossing
    (its curve ended unresolved nearby) up to the next one it is not checked.
    A period-2 walk where continuation has the period-1 walk stable is a
    coexisting attractor (the standing start may settle on either): inside
    the band before a subcritical doubling where its own period-2 walk is
    stable too, or another period-2 walk, which the continuation does not
    follow; reported, not a disagreement. In the column of the one-parameter
    diagram's f_n, where that band is known (`band`: from where its period-2
    branch turns unstable or folds, to the doubling), the scan must see one
    of the two walks between the band's far edge and the crossing."""
    bad, notes = [], []
    tol = step * (1 + 1e-6)
    at = [x for x, _ in xs]

    def stable_one(phi: float) -> bool:
        return sum(x < phi for x in at) % 2 == 0

    def near(phi: float) -> bool:
        return any(abs(phi - x) <= tol for x in at)

    def unknown(phi: float) -> bool:
        below = [(x, o) for x, o in xs if x < phi]
        return bool(below) and below[-1][1] and not stable_one(phi)

    skipped = [phi for phi, c in zip(v, cls) if c in ("walk1", "walk2") and unknown(phi)]
    if skipped:
        notes.append(f"{len(skipped)} walk(s) past the open crossing not checked")
    for phi, c in zip(v, cls):
        if c == "walk1" and not stable_one(phi) and not near(phi) and not unknown(phi):
            bad.append(f"a stable period-1 walk at {phi:.3f}, where continuation has it unstable")
    coexisting = [phi for phi, c in zip(v, cls) if c == "walk2" and stable_one(phi) and not near(phi)]
    if coexisting:
        inside = [phi for phi in coexisting if band is not None and band[0] == band[0]
                  and band[0] - tol <= phi <= band[1] + tol]
        notes.append(f"{len(coexisting)} period-2 walk(s) where the period-1 walk is stable too"
                     + (f" ({len(inside)} in the doubling's band)" if inside else ""))
    if band is not None and band[0] == band[0]:
        for i, x in enumerate(at):
            if i % 2 or not (v[0] + tol < x <= v[-1]):
                continue  # stability regained going up, or the crossing outside the grid
            if not any(band[0] - tol <= phi <= x + tol and c in ("walk1", "walk2") for phi, c in zip(v, cls)):
                bad.append(f"neither walk between {band[0]:.4f} and the crossing at {x:.4f}, where both are stable")
    return bad, notes


def plane_rows(grid: pl.DataFrame, curve: pl.DataFrame, param: str, param2: str,
               both: tuple[float, float, float] | None) -> list[dict]:
    """Per column (value of param2) of the grid: the curves' crossings, the
    scan's period-1 and period-2 walks, and what disagrees."""
    cols = sorted(grid[param2].unique().to_list())
    spacing = float(np.min(np.diff(cols))) if len(cols) > 1 else np.inf
    OPEN_REACH[0] = spacing
    out = []
    for col, g in grid.sort(param2, param).group_by(param2, maintain_order=True):
        col = float(col[0])
        v, cls = g[param].to_numpy(), g["cls"].to_list()
        step = float(np.min(np.diff(v))) if len(v) > 1 else float("nan")
        xs = crossings(curve, col)
        band = None
        if both is not None:
            at, phi_pd, edge = both
            # The diagram bounds the band only in the column at its f_n.
            band = (edge, phi_pd) if abs(col - at) <= spacing / 2 else (float("nan"), float("nan"))
        out.append({"param2": col, "crossings": xs, "one": ranges(v, [c == "walk1" for c in cls], step),
                    "two": ranges(v, [c == "walk2" for c in cls], step), "band": band,
                    "check": check_column(v, cls, xs, step, band)})
    return out


def plane(points: Path, samples: Path, out: Path, check: bool, title: str | None) -> Path:
    if model_of(points) != model_of(samples):
        sys.exit(f"continuation: {samples} is at model {model_of(samples)}, {points} at {model_of(points)}")
    curve = pl.read_parquet(companion(points, "curve"))
    param, param2 = curve["param"][0], curve["param2"][0]
    grid = scan_grid(samples, param, param2)
    both = coexistence(points, param2)
    rows = plane_rows(grid, curve, param, param2, both)
    fig, ax = plt.subplots(figsize=(8, 6.4))
    styles = {"walk1": ("o", "#2ca02c", "walk, period 1 (stable cycle)"),
              "walk2": ("s", "#ff7f0e", "walk, period 2 (stable cycle)")}
    other = grid.filter(~pl.col("cls").is_in(list(styles)))
    ax.scatter(other[param], other[param2], marker="x", s=14, color="#9e9e9e", lw=0.8,
               label="another gait, period, or failure")
    for cls, (marker, color, name) in styles.items():
        g = grid.filter(pl.col("cls") == cls)
        ax.scatter(g[param], g[param2], marker=marker, s=22, color=color, label=f"scan: {name}")
    labelled = set()
    for (_, kind), g in curve.sort("curve", "index").group_by(["curve", "kind"], maintain_order=True):
        kind = str(kind)
        _, color, name = KIND_STYLE[kind]
        ax.plot(g["value"], g["value2"], color=color, lw=2,
                label=None if kind in labelled else f"{name} curve (rtw-scan continuation --curve)")
        labelled.add(kind)
    if both is not None:
        at, phi_pd, edge = both
        ax.plot([edge, phi_pd], [at, at], color="#1f77b4", lw=4, alpha=0.5, solid_capstyle="butt",
                label="both walks stable (one-parameter diagram)")
    ax.set_xlabel(SYMBOL.get(param, param))
    ax.set_ylabel(SYMBOL.get(param2, param2))
    ax.legend(fontsize=7, loc="best")
    full = titled(fig, title or f"where the walk is stable: ({param}, {param2})", points, 95)
    fig.tight_layout()
    save(fig, out, full)
    bad = 0
    print(f"| {param2} | curve crosses at {param} | scan: stable period-1 walk | scan: stable period-2 walk | agrees |")
    print("|---:|---|---|---|---|")
    for r in rows:
        fails, notes = r["check"]
        bad += len(fails)
        verdict = "NO: " + "; ".join(fails) if fails else "yes"
        if notes:
            verdict += " (" + "; ".join(notes) + ")"
        xs = ", ".join(f"{x:.4f}" + (" (open)" if o else "") for x, o in r["crossings"]) or "none"
        print(f"| {r['param2']:.4g} | {xs} | {r['one']} | {r['two']} | {verdict} |")
    if check and bad:
        sys.exit(f"continuation: the continuation disagrees with the brute-force scan at {bad} point(s)")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest="cmd", required=True)
    d = sub.add_parser("diagram")
    d.add_argument("points", type=Path)
    d.add_argument("--sweep", type=Path)
    d.add_argument("--out", type=Path)
    d.add_argument("--title")
    p = sub.add_parser("plane")
    p.add_argument("points", type=Path)
    p.add_argument("samples", type=Path)
    p.add_argument("--out", type=Path)
    p.add_argument("--check", action="store_true")
    p.add_argument("--title")
    a = ap.parse_args()
    if a.cmd == "diagram":
        out = diagram(a.points, a.out or a.points.with_suffix(".png"), a.sweep, a.title)
    else:
        out = plane(a.points, a.samples, a.out or a.points.with_name(a.points.stem + ".plane.png"),
                    a.check, a.title)
    print(f"continuation: wrote {out}", file=sys.stderr)


if __name__ == "__main__":
    main()
