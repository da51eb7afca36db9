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
  prints, per column of the grid, where the scan's period-1 walk turns into a
  period-2 walk and where the period-doubling curve crosses that column, and
  with --check fails unless they agree to the grid's resolution. When the
  doubling is subcritical (the period-2 branch folds back over the side where
  the period-1 walk is stable, read from the one-parameter diagram), a column
  whose first period-2 walk comes before the curve agrees if no stable
  period-1 walk lies beyond the curve: both walks are attractors there.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from figures import DPI  # noqa: E402

SYMBOL = {"phi": "φ [rad]", "length": "L [m]", "rho": "ρ [kg/m]", "alpha": "α", "fn": "f_n [Hz]",
          "zeta": "ζ"}
KIND_STYLE = {"period_doubling": ("o", "#d62728", "period doubling"),
              "fold": ("s", "#1f77b4", "fold"),
              "branch_point": ("^", "#2ca02c", "branch point"),
              "neimark_sacker": ("D", "#9467bd", "Neimark–Sacker")}
PERIOD_COLOR = {1: "#000000", 2: "#ff7f0e", 4: "#8c564b"}


def companion(points: Path, what: str) -> Path:
    return points.with_name(f"{points.stem}.{what}.parquet")


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
    fig.suptitle(title or f"continuation in {param}", fontsize=10)
    fig.text(0.01, 0.005, f"rtw-scan continuation; {wall} s; variant {meta.get(b'rtw.variant', b'?').decode()[:110]}",
             fontsize=6, color="#666666")
    fig.tight_layout(rect=(0, 0.015, 1, 1))
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
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


def boundary_rows(grid: pl.DataFrame, curve: pl.DataFrame, param: str, param2: str) -> list[dict]:
    """Per column (value of param2) of the grid: the last `walk1` point
    before the first `walk2` above it in param (the scan's period-doubling
    boundary, to its resolution), and the period-doubling curve's param
    there (linear interpolation in param2)."""
    pd = curve.filter(pl.col("kind").cast(str) == "period_doubling").sort("value2")
    out = []
    for col, g in grid.sort(param2, param).group_by(param2, maintain_order=True):
        col = float(col[0])
        v, cls = g[param].to_numpy(), g["cls"].to_list()
        step = float(np.min(np.diff(v))) if len(v) > 1 else float("nan")
        ones = [i for i, c in enumerate(cls) if c == "walk1"]
        twos = [i for i, c in enumerate(cls) if c == "walk2" and ones and i > ones[0]]
        if not ones or not twos:
            scan_lo = scan_hi = float("nan")
        else:
            hi = twos[0]
            lo = max(i for i in ones if i < hi)
            scan_lo, scan_hi = float(v[lo]), float(v[hi])
        crossing = float("nan")
        if not pd.is_empty() and pd["value2"].min() <= col <= pd["value2"].max():
            crossing = float(np.interp(col, pd["value2"].to_numpy(), pd["value"].to_numpy()))
        last_one = float(v[ones[-1]]) if ones else float("nan")
        out.append({"param2": col, "scan_lo": scan_lo, "scan_hi": scan_hi, "curve": crossing, "step": step,
                    "last_one": last_one})
    return out


def subcritical(points: Path) -> bool:
    """Is the period doubling of the one-parameter diagram subcritical: does
    the period-2 branch born there reach back over the side where the
    period-1 walk is stable (a fold of that branch beyond the doubling)?
    Then both walks are attractors over a band before the doubling, and a
    run from the standing start may settle on either there."""
    pts = pl.read_parquet(points)
    special = pl.read_parquet(companion(points, "special"))
    pd = special.filter((pl.col("kind").cast(str) == "period_doubling"))
    if pd.is_empty():
        return False
    phi_pd, branch = float(pd["value"][0]), int(pd["branch"][0])
    one = pts.filter((pl.col("branch") == branch) & pl.col("stable"))
    if one.is_empty():
        return False
    stable_side = np.sign(float(one["value"].mean()) - phi_pd)
    two = pts.filter(pl.col("period") == 2)
    return bool(((two["value"].to_numpy() - phi_pd) * stable_side > 0).any())


def plane(points: Path, samples: Path, out: Path, check: bool, title: str | None) -> Path:
    curve = pl.read_parquet(companion(points, "curve"))
    param, param2 = curve["param"][0], curve["param2"][0]
    grid = scan_grid(samples, param, param2)
    rows = boundary_rows(grid, curve, param, param2)
    bistable = subcritical(points)
    fig, ax = plt.subplots(figsize=(8, 6))
    styles = {"walk1": ("o", "#2ca02c", "walk, period 1 (stable cycle)"),
              "walk2": ("s", "#ff7f0e", "walk, period 2")}
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
    ax.set_xlabel(SYMBOL.get(param, param))
    ax.set_ylabel(SYMBOL.get(param2, param2))
    ax.legend(fontsize=8, loc="best")
    ax.set_title(title or f"where the walk is stable: ({param}, {param2})", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    bad = 0
    print(f"| {param2} | scan: last period-1 walk | scan: first period-2 walk | period-doubling curve | agrees |")
    print("|---:|---:|---:|---:|---|")
    for r in rows:
        if np.isnan(r["scan_lo"]) or np.isnan(r["curve"]):
            verdict = "no period-1 → period-2 walk change in the scan's column" if np.isnan(r["scan_lo"]) \
                else "outside the curve's range"
        elif bistable and r["scan_hi"] < r["curve"] - r["step"]:
            # A subcritical doubling: before it, the period-1 and period-2
            # walks are both attractors and the standing start may settle on
            # either, so the first period-2 walk may come early. What must
            # still hold is that no stable period-1 walk lies beyond the
            # curve, where continuation says the period-1 cycle is unstable.
            ok = r["last_one"] <= r["curve"] + r["step"]
            bad += not ok
            verdict = "yes (both walks before the subcritical doubling)" if ok else "NO"
        else:
            # The scan resolves the boundary to one grid step: the curve must
            # lie within a step of the bracket [last period-1, first period-2].
            ok = r["scan_lo"] - r["step"] <= r["curve"] <= r["scan_hi"] + r["step"]
            bad += not ok
            verdict = "yes" if ok else "NO"
        print(f"| {r['param2']:.4g} | {r['scan_lo']:.4f} | {r['scan_hi']:.4f} | {r['curve']:.4f} | {verdict} |")
    if check and bad:
        sys.exit(f"continuation: the period-doubling curve disagrees with the scan in {bad} column(s)")
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
