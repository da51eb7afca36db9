"""Every figure of results/figures/ from rtw-scan's output.

Run through scripts/figures.sh, which sets up the venv and builds rtw-scan.
Inputs: the scans results/paper, results/fig-s2 and results/fig-s3
(samples.parquet each), rtw-scan's own k-means assignment of the paper
scan's failures (`rtw-scan cluster --assignments`), and three trajectories
this script records for the gait gallery and the walk animation (walk.gif):
with the Python package (rtw.simulate, rtw.trace) when it is installed,
else with `rtw-scan simulate --json --trace`. Nothing here recomputes a
simulation result: every number drawn is read from a file rtw-scan wrote,
or from a run of the model. The star is drawn by the package's rtw.draw
(the installed package: its labels come from the compiled part).

    python scripts/figures.py --bin target/release/rtw-scan [--out results/figures]
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tomllib
from dataclasses import dataclass
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import polars as pl  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

from rtw.animation import animate  # noqa: E402
from rtw.draw import (  # noqa: E402
    FAILED,
    OUTCOME_COLOR,
    ROD_COLOR,
    STABLE,
    STATE_COLOR,
    STATE_NAMES,
    GeometryError,
    Trace,
    check_geometry,
    draw_star,
    timeline,
)

from rtwscripts import DEFAULT_VARIANT, DPI, ROOT  # noqa: E402
from rtwscripts.stats import permutation_p, wilson  # noqa: E402

CLUSTER_COLOR = ("#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#17becf")
KIND_MARKER = {"collapse": "^", "stall": "o"}

# The article's walking example (Fig. 7(a), docs/model.md §1), for the gait gallery.
FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)
# Trace sampling for the gait gallery (events are recorded as well).
TRACE_DT = 0.004
PARAMS = ("length", "rho", "alpha", "fn", "zeta", "phi")


# --------------------------------------------------------------------- inputs


@dataclass
class Scan:
    """A scan's rows with the metadata rtw-scan stored in the file."""

    path: Path
    df: pl.DataFrame
    variant: str
    config: dict

    @classmethod
    def read(cls, path: Path) -> "Scan":
        if not path.exists():
            sys.exit(
                f"figures: {path} is missing: run the scan first "
                f"(cargo run --release -p rtw-scan -- run configs/{path.parent.name}.toml --out results/{path.parent.name})"
            )
        meta = pq.read_metadata(path).metadata or {}
        variant = meta.get(b"rtw.variant", b"(unknown variant)").decode()
        config = tomllib.loads(meta.get(b"rtw.config", b"").decode())
        df = pl.read_parquet(path).with_columns(pl.col("outcome").cast(pl.Utf8))
        return cls(path, df, variant, config)

    def footer(self) -> str:
        name = self.path.relative_to(ROOT) if self.path.is_relative_to(ROOT) else self.path
        return f"{name} · model variant: {self.variant}"


# The literal model's choices (docs/model.md §9); a title names only what a variant changes.
DEFAULTS = {"mu": "inf", "slack": "false", "damping": "along", "normalization": "supplementary",
            "initial": "rigid_star(omega=-2)"}


def variant_tag(variant: str) -> str:
    """A short name of a model variant for titles: s = ℓ₀/r and every §9 option off its default."""
    kv = dict(p.split("=", 1) for p in variant.split() if "=" in p)
    s = float(kv.get("rest_length_ratio", "nan"))
    tag = f"s = {s:g}" + (" (paper-faithful S5–S6)" if s == 0 else " (prestressed strings)")
    rest = [f"{k}={v}" for k, v in kv.items() if k in DEFAULTS and v != DEFAULTS[k]]
    return "variant " + ", ".join([tag] + rest)


def add_footer(fig, text: str) -> None:
    """The data source and full variant, as the figure's bottom label (constrained layout makes room)."""
    fig.supxlabel(text, fontsize=7.5, color="#444444", wrap=True)


def save(fig, out: Path, name: str) -> Path:
    path = out / f"{name}.png"
    fig.savefig(path, dpi=DPI)
    plt.close(fig)
    print(f"figures: wrote {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path}")
    return path


# -------------------------------------------------------------------- Fig. S2


def fig_s2(scan: Scan, out: Path) -> Path:
    df = scan.df.sort("fn")
    fn = df["fn"].to_numpy()
    stable = df["outcome"].is_in(STABLE).to_numpy()
    fig, ax = plt.subplots(figsize=(11, 5.8), constrained_layout=True)
    lo, hi = fn.min(), fn.max()
    grid = np.linspace(lo, hi, 2)
    ax.plot(grid, grid, color="black", lw=1, ls="--", label=r"$f_w = f_n$")
    ax.plot(grid, math.sqrt(3) * grid, color="black", lw=1, ls=":", label=r"$f_w = \sqrt{3}\,f_n$ (true mode, docs/model.md §7)")
    # Squares (new-foot rate) under circles (all touchdowns): where the two
    # definitions agree, a dot sits inside a square.
    for col, marker, size, ls, name in (
        ("f_w_newfoot", "s", 70, "--", r"$f_w^{\rm new}$: touchdowns on a new foot per second (hollow squares)"),
        ("f_w", "o", 22, "-", r"$f_w$: all touchdowns per second (dots)"),
    ):
        y = df[col].to_numpy()
        ax.plot(fn, y, color="#999999", lw=0.7, ls=ls, zorder=1)
        for label in STABLE:
            m = (df["outcome"] == label).to_numpy()
            c = OUTCOME_COLOR[label]
            ax.scatter(fn[m], y[m], marker=marker, s=size, edgecolors=c, zorder=3 if marker == "s" else 4,
                       facecolors=c if marker == "o" else "white", linewidths=1.3)
        ax.scatter(fn[~stable], y[~stable], marker="x", s=40, color="black", zorder=5)
        ax.plot([], [], marker=marker, ls=ls, color="#555555", markersize=8 if marker == "s" else 5,
                markerfacecolor="#555555" if marker == "o" else "white", label=name)
    for label in STABLE:
        n = int((df["outcome"] == label).sum())
        ax.plot([], [], marker="o", ls="none", color=OUTCOME_COLOR[label], label=f"{label} ({n} of {len(df)})")
    n_failed = int((~stable).sum())
    ax.plot([], [], marker="x", ls="none", color="black", label=f"not stable ({n_failed}): collapse/stall/diverged")
    ax.set_xlabel(r"design eigen-frequency $f_n$ [Hz]")
    ax.set_ylabel(r"walking frequency $f_w$ [Hz]")
    p = df.row(0, named=True)
    ax.set_title(
        "Fig. S2: walking frequency against $f_n$\n"
        f"L = {p['length']}, ρ = {p['rho']}, α = {p['alpha']}, ζ = {p['zeta']}, φ = {p['phi']} rad; "
        f"{variant_tag(scan.variant)}",
        fontsize=10,
    )
    ax.set_xlim(lo - 0.1, hi + 0.1)
    ax.set_ylim(0, max(math.sqrt(3) * hi, np.nanmax(df["f_w"].to_numpy())) * 1.05)
    ax.grid(alpha=0.3)
    fig.legend(fontsize=8, loc="outside upper center", ncol=4)
    add_footer(fig, scan.footer())
    return save(fig, out, "fig-s2")


# -------------------------------------------------------------------- Fig. S3


def fig_s3(scan: Scan, out: Path) -> Path:
    lengths = sorted(scan.df["length"].unique().to_list())
    fig, axes = plt.subplots(1, len(lengths), figsize=(4.6 * len(lengths) + 2.6, 5.0), sharey=True,
                             constrained_layout=True, squeeze=False)
    for ax, length in zip(axes[0], lengths):
        df = scan.df.filter(pl.col("length") == length).sort("phi")
        phi = df["phi"].to_numpy()
        ok = df["outcome"].is_in(STABLE).to_numpy()
        ax.axhline(50, color="black", lw=0.8, ls="--", zorder=0)
        for state in STATE_NAMES:
            y = 100 * df[state.lower()].to_numpy()
            c = STATE_COLOR[state]
            ax.plot(phi, y, color=c, lw=1.4, zorder=2)
            ax.scatter(phi[ok], y[ok], color=c, s=26, zorder=3)
            ax.scatter(phi[~ok], y[~ok], facecolors="white", edgecolors=c, s=26, zorder=3, linewidths=1.2)
        # The outcome of each point, as a letter strip along the top.
        for x, label in zip(phi, df["outcome"].to_list()):
            ax.text(x, 103, label[0].upper() if label in STABLE else "×", ha="center", va="bottom",
                    fontsize=8, color=OUTCOME_COLOR[label], fontweight="bold")
        ax.set_title(f"L = {length} m", fontsize=10)
        ax.set_xlabel("slope φ [rad]")
        ax.set_ylim(-3, 110)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("time in contact state [% of analysis window]")
    handles = [Line2D([], [], color=STATE_COLOR[s], marker="o", label=s) for s in STATE_NAMES]
    handles += [
        Line2D([], [], color="#555555", marker="o", markerfacecolor="white", ls="none", label="not stable (hollow)"),
        Line2D([], [], color="black", ls="--", lw=0.8, label="50 % (paper: SLSP ≈ DLSP ≈ 50 %)"),
    ]
    handles += [Line2D([], [], color=OUTCOME_COLOR[k], marker=f"${k[0].upper()}$", ls="none", label=k) for k in STABLE]
    handles += [Line2D([], [], color=OUTCOME_COLOR["stall"], marker="$×$", ls="none", label="collapse/stall")]
    fig.legend(handles=handles, fontsize=8, loc="outside right upper")
    p = scan.df.row(0, named=True)
    fig.suptitle(
        f"Fig. S3: contact-state fractions against slope; ρ = {p['rho']}, α = {p['alpha']}, "
        f"f_n = {p['fn']} Hz, ζ = {p['zeta']}\n{variant_tag(scan.variant)}",
        fontsize=10,
    )
    add_footer(fig, scan.footer() + " · letters: outcome of each run (S skip, W walk, C crawl, × failed)")
    return save(fig, out, "fig-s3")


# -------------------------------------------------------------------- Fig. S4


def cluster_assignments(binary: Path, samples: Path, out_file: Path) -> tuple[pl.DataFrame, dict]:
    """rtw-scan's own k-means of the failures: per failure its cluster, and the centres."""
    subprocess.run([str(binary), "cluster", str(samples), "--assignments", str(out_file)],
                   check=True, stdout=subprocess.DEVNULL)
    meta = pq.read_metadata(out_file).metadata
    return pl.read_parquet(out_file), json.loads(meta[b"rtw.clusters"])


def fig_s4(scan: Scan, binary: Path, data_dir: Path, out: Path) -> Path:
    assign, clusters = cluster_assignments(binary, scan.path, data_dir / "paper-clusters.parquet")
    fig = plt.figure(figsize=(12.5, 10.8), constrained_layout=True)
    # A third, short row holds the legend (outside-legend placement collides
    # with the suptitle or the footer under constrained layout).
    gs = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.14])
    ax3 = fig.add_subplot(gs[0, 0], projection="3d")
    projections = [("alpha", "fn"), ("alpha", "phi"), ("fn", "phi")]
    axes2 = [fig.add_subplot(gs[0, 1]), fig.add_subplot(gs[1, 0]), fig.add_subplot(gs[1, 1])]
    axis_label = {"alpha": "connection ratio α", "fn": "$f_n$ [Hz]", "phi": "slope φ [rad]"}
    params = scan.config.get("params", {})
    stable = scan.df.filter(pl.col("outcome").is_in(STABLE))

    def style(j: int, kind: str) -> dict:
        c = CLUSTER_COLOR[j % len(CLUSTER_COLOR)]
        filled = kind == "collapse"
        return dict(marker=KIND_MARKER[kind], s=30, edgecolors=c, facecolors=c if filled else "none",
                    linewidths=1.1, alpha=0.9)

    for j, c in enumerate(clusters["clusters"]):
        for kind in FAILED:
            sel = assign.filter((pl.col("cluster") == j + 1) & (pl.col("outcome") == kind))
            if sel.is_empty():
                continue
            ax3.scatter(sel["alpha"], sel["fn"], sel["phi"], **style(j, kind))
            for ax, (x, y) in zip(axes2, projections):
                ax.scatter(sel[x], sel[y], **style(j, kind), zorder=3)
        centre = {"alpha": c["alpha"], "fn": c["fn"], "phi": c["phi"]}
        cc = CLUSTER_COLOR[j % len(CLUSTER_COLOR)]
        ax3.scatter([centre["alpha"]], [centre["fn"]], [centre["phi"]], marker="*", s=420, color=cc,
                    edgecolors="black", linewidths=1.2, depthshade=False)
        for ax, (x, y) in zip(axes2, projections):
            ax.scatter([centre[x]], [centre[y]], marker="*", s=420, color=cc, edgecolors="black",
                       linewidths=1.2, zorder=5)
    for ax, (x, y) in zip(axes2, projections):
        ax.scatter(stable[x], stable[y], s=5, color="#cccccc", zorder=1)
        ax.set_xlabel(axis_label[x])
        ax.set_ylabel(axis_label[y])
        for name, setter in ((x, ax.set_xlim), (y, ax.set_ylim)):
            rng = params.get(name, {}).get("uniform") if isinstance(params.get(name), dict) else None
            if rng:
                pad = 0.03 * (rng[1] - rng[0])
                setter(rng[0] - pad, rng[1] + pad)
        ax.grid(alpha=0.3)
    ax3.set_xlabel("α")
    ax3.set_ylabel("$f_n$ [Hz]")
    ax3.set_zlabel("φ [rad]")
    ax3.view_init(elev=22, azim=-58)
    handles = []
    for j, c in enumerate(clusters["clusters"]):
        cc = CLUSTER_COLOR[j % len(CLUSTER_COLOR)]
        handles.append(Patch(color=cc, label=(
            f"cluster {j + 1}: {c['name']} — {c['size']} ({c['collapse']} collapse, {c['stall']} stall); "
            f"centre α = {c['alpha']:.3f}, f_n = {c['fn']:.2f} Hz, φ = {c['phi']:.3f}")))
    handles += [
        Line2D([], [], marker="^", color="#444444", ls="none", label="collapse (filled)"),
        Line2D([], [], marker="o", color="#444444", markerfacecolor="none", ls="none", label="stall (hollow)"),
        Line2D([], [], marker="*", color="#888888", markeredgecolor="black", markersize=14, ls="none",
               label="cluster centre (rtw-scan k-means)"),
        Line2D([], [], marker="o", color="#cccccc", markersize=4, ls="none", label="stable samples (2-D views)"),
    ]
    key = fig.add_subplot(gs[2, :])
    key.axis("off")
    key.legend(handles=handles, loc="center", ncol=2, fontsize=8.5, frameon=False)
    sil = clusters.get("silhouette")
    n = len(scan.df)
    fig.suptitle(
        f"Fig. S4: the {clusters['failures']} failures of {n} samples in (α, f_n, φ), "
        f"k-means k = {clusters['k']} on standardized coordinates"
        + (f", silhouette {sil:.2f}" if sil is not None else "")
        + f"\n{variant_tag(scan.variant)}",
        fontsize=11,
    )
    add_footer(fig, scan.footer() + " · clusters: rtw-scan cluster --assignments")
    return save(fig, out, "fig-s4")


# ------------------------------------------------------- failure rate (binned)


def failure_rates(scan: Scan, out: Path, nbins: int = 8) -> Path:
    df = scan.df
    failed = df["outcome"].is_in(FAILED).to_numpy().astype(float)
    collapse = (df["outcome"] == "collapse").to_numpy()
    overall = failed.mean()
    lo_all, hi_all = wilson(np.array([failed.sum()]), np.array([len(failed)]))
    names = [("rho", "ρ [kg/m]"), ("zeta", "ζ"), ("alpha", "α"), ("fn", "$f_n$ [Hz]"), ("phi", "φ [rad]")]
    params = scan.config.get("params", {})
    fig, grid = plt.subplots(2, 3, figsize=(13, 8.2), constrained_layout=True)
    axes = grid.flat
    for ax, (col, label) in zip(axes, names):
        x = df[col].to_numpy()
        spec = params.get(col)
        lo, hi = spec["uniform"] if isinstance(spec, dict) and "uniform" in spec else (x.min(), x.max())
        edges = np.linspace(lo, hi, nbins + 1)
        b = np.clip(np.digitize(x, edges) - 1, 0, nbins - 1)
        n = np.bincount(b, minlength=nbins)
        k = np.bincount(b, weights=failed, minlength=nbins)
        kc = np.bincount(b, weights=collapse.astype(float), minlength=nbins)
        centres = 0.5 * (edges[1:] + edges[:-1])
        rate = np.divide(k, n, out=np.zeros(nbins), where=n > 0)
        wl, wh = wilson(k, n)  # at k = 0 the lower end is 0 up to rounding: clipped below
        ax.axhspan(100 * lo_all[0], 100 * hi_all[0], color="#dddddd", zorder=0)
        ax.axhline(100 * overall, color="#888888", lw=1, zorder=1)
        ax.errorbar(centres, 100 * rate, yerr=100 * np.clip([rate - wl, wh - rate], 0, None), fmt="o-", color="black",
                    capsize=3, lw=1.2, zorder=3)
        ax.plot(centres, 100 * np.divide(kc, n, out=np.zeros(nbins), where=n > 0), "^--",
                color=OUTCOME_COLOR["collapse"], lw=1, ms=5, zorder=2)
        ax.plot(centres, 100 * np.divide(k - kc, n, out=np.zeros(nbins), where=n > 0), "o--",
                color=OUTCOME_COLOR["stall"], lw=1, ms=4, mfc="white", zorder=2)
        rounds = 2000
        stat, p = permutation_p(b, failed, nbins, rounds=rounds, seed=1)
        # No shuffle reached the observed χ²: p is only bounded by the number of shuffles.
        p_text = f"< {1 / rounds:.1g}" if p <= 1 / (rounds + 1) else f"= {p:.2g}"
        ax.set_title(f"{label.split(' ')[0]}:  χ² = {stat:.1f} ({nbins - 1} dof), permutation p {p_text}")
        ax.set_xlabel(label)
        ax.set_xlim(lo, hi)
        ax.set_ylim(bottom=-2)
        ax.grid(alpha=0.3)
    for ax in (grid[0][0], grid[1][0]):
        ax.set_ylabel("failure rate [% of samples in bin]")
    ymax = max(ax.get_ylim()[1] for ax in grid.flat[:5])
    for ax in grid.flat[:5]:
        ax.set_ylim(-2, ymax)
    key = grid[1][2]
    key.axis("off")
    key.legend(handles=[
        Line2D([], [], marker="o", color="black", label="failed (collapse + stall), Wilson 95 % interval"),
        Line2D([], [], marker="^", ls="--", color=OUTCOME_COLOR["collapse"], label="collapse"),
        Line2D([], [], marker="o", ls="--", mfc="white", color=OUTCOME_COLOR["stall"], label="stall"),
        Patch(color="#dddddd", label=f"overall failure rate {100 * overall:.1f} % and its interval"),
    ], loc="upper left", fontsize=9, frameon=False)
    key.text(0.0, 0.45,
             f"{len(df)} samples, {nbins} equal bins over each\nparameter's sampled range.\n\n"
             f"χ²: failure against bin (2 × {nbins} table);\n"
             "p: share of 2000 shuffles of the failure\nlabels with χ² at least as large\n"
             "(small p: the rate depends on the parameter).\n\n"
             "Paper (Fig. S4): failure is nearly independent\nof ρ and ζ.",
             transform=key.transAxes, va="top", fontsize=9)
    fig.suptitle(f"Failure rate against each parameter — paper scan, {variant_tag(scan.variant)}", fontsize=11)
    add_footer(fig, scan.footer())
    return save(fig, out, "failure-rate")


# --------------------------------------------------------------- gait gallery


@dataclass
class Gait:
    name: str
    caption: str
    params: dict
    sets: list[str]
    # A config whose [simulation] table the run takes first (then `sets`).
    config: Path | None = None


def native():
    """The compiled package (rtw.simulate, rtw.trace), or None when only the
    pure-Python part is importable (then the runs go through rtw-scan)."""
    try:
        import rtw._rtw  # noqa: F401
    except ImportError:
        return None
    import rtw

    return rtw


def simulate(binary: Path, g: Gait, trace_file: Path) -> tuple[dict, Trace]:
    """One traced run, its metrics and its trace (also written to trace_file):
    rtw.simulate + rtw.trace if the package is installed, else
    `rtw-scan simulate ... --json --trace`."""
    rtw = native()
    if rtw is not None:
        inputs = {key: float(g.params[key]) for key in PARAMS}
        options = {k: tomllib.loads(f"v = {v}")["v"] for k, v in (s.split("=", 1) for s in g.sets)}
        config = None if g.config is None else str(g.config)
        print(f"figures: rtw.simulate/rtw.trace({inputs}, config={config}, options={options})", file=sys.stderr)
        m = rtw.simulate(**inputs, config=config, options={**options, "trace_dt": TRACE_DT}).to_dict()
        table = rtw.trace(**inputs, config=config, options=options, dt=TRACE_DT)
        pq.write_table(table, trace_file)
        return m, Trace.read(trace_file)
    args = [str(binary), "simulate"]
    for key in PARAMS:
        args += [f"--{key}", repr(float(g.params[key]))]
    if g.config is not None:
        args += ["--config", str(g.config)]
    for s in g.sets + [f"trace_dt={TRACE_DT}"]:
        args += ["--set", s]
    args += ["--json", "--trace", str(trace_file)]
    print("figures: " + " ".join(args[1:]), file=sys.stderr)
    res = subprocess.run(args, check=True, capture_output=True, text=True)
    return json.loads(res.stdout), Trace.read(trace_file)


def pick_crawl(paper: Scan) -> dict:
    """The paper scan's clearest crawl: the largest TLSP fraction among periodic
    crawls (period ≥ 1), else among all crawls."""
    crawls = paper.df.filter(pl.col("outcome") == "crawl")
    if crawls.is_empty():
        sys.exit(f"figures: no crawl in {paper.path}: the gait gallery needs one")
    periodic = crawls.filter(pl.col("period") >= 1)
    pool = periodic if not periodic.is_empty() else crawls
    return pool.sort("tlsp", descending=True).row(0, named=True)


def checked(trace: Trace, m: dict) -> Trace:
    """The trace, once its drawing is shown to be the model's: the connection
    radius rtw.draw derives from (L, α) is the run's, and check_geometry holds
    with the run's stiffness."""
    if not math.isclose(trace.design.r, float(m["r"]), rel_tol=1e-12):
        sys.exit(f"figures: rtw.draw's r = {trace.design.r} is not the run's {m['r']}: geometry mismatch")
    try:
        check_geometry(trace, float(m["k"]))
    except GeometryError as e:
        sys.exit(f"figures: {e}")
    return trace


FIG7A_TEXT = "Fig. 7(a) point: L = 0.8, ρ = 2.5, α = 0.125, f_n = 3.269, ζ = 0.0514, φ = 0.15"
WALK = Gait("walk", f"{FIG7A_TEXT}; the default model (variant {DEFAULT_VARIANT})", FIG7A, [],
            Path("configs/variants") / f"{DEFAULT_VARIANT}.toml")


def steady_touchdown(tr: Trace, m: dict) -> float:
    """After the transient: the first touchdown (rods on the ground rise)
    past three quarters of the run."""
    t_end = float(m["t_end"])
    rise = np.nonzero((np.diff(tr.state) > 0) & (tr.t[1:] >= 0.75 * t_end))[0]
    return float(tr.t[rise[0] + 1]) if len(rise) else 0.75 * t_end


def gait_gallery(binary: Path, paper: Scan, data_dir: Path, out: Path, nframes: int = 8) -> Path:
    crawl = pick_crawl(paper)
    paper_config = data_dir / "paper-config.toml"
    paper_config.write_text((pq.read_metadata(paper.path).metadata or {})[b"rtw.config"].decode())
    gaits = [
        WALK,
        Gait("skip", f"{FIG7A_TEXT}; the paper-faithful model (variant literal: S5–S6 literally, s = 0)",
             FIG7A, [], Path("configs/variants/literal.toml")),
        # The crawl is re-run with the paper scan's own [simulation] table (its
        # variant, whatever the default is), so it is that scan's row again.
        Gait("crawl",
             f"paper-scan sample {crawl['sample_id']}: L = {crawl['length']:.2g}, ρ = {crawl['rho']:.3f}, "
             f"α = {crawl['alpha']:.3f}, f_n = {crawl['fn']:.3f}, ζ = {crawl['zeta']:.4f}, φ = {crawl['phi']:.3f}; "
             f"the paper scan's {variant_tag(paper.variant)}",
             {k: crawl[k] for k in ("length", "rho", "alpha", "fn", "zeta", "phi")},
             [], paper_config),
    ]
    fig = plt.figure(figsize=(15, 5.0 * len(gaits)))
    outer = fig.add_gridspec(len(gaits), 1, hspace=0.32, top=0.955, bottom=0.04, left=0.06, right=0.99)
    for gi, g in enumerate(gaits):
        m, tr = simulate(binary, g, data_dir / f"trace-{g.name}.parquet")
        if m["outcome"] != g.name:
            print(f"figures: warning: the {g.name} example came out {m['outcome']}", file=sys.stderr)
        if g.name == "crawl" and m["tlsp"] != crawl["tlsp"]:
            sys.exit(f"figures: sample {crawl['sample_id']} re-run gives TLSP {m['tlsp']}, the scan {crawl['tlsp']}")
        length = float(g.params["length"])
        checked(tr, m)
        t_start = steady_touchdown(tr, m)
        step = 1.0 / m["f_w_newfoot"] if m["f_w_newfoot"] > 0 else 0.5
        span = min(max(2 * step, 0.3), 1.5)
        frames = t_start + np.linspace(0, span, nframes)
        inner = outer[gi].subgridspec(3, nframes, height_ratios=[2.6, 0.75, 0.75], hspace=0.08, wspace=0.02)
        window = 1.45 * length
        for fi, tf in enumerate(frames):
            ax = fig.add_subplot(inner[0, fi])
            i = int(tr.nearest(tf))
            draw_star(ax, tr, i, window)
            ax.set_title(f"t = {tr.t[i]:.3f} s", fontsize=8, pad=1)
        ax_modes = fig.add_subplot(inner[1, :])
        ax_state = fig.add_subplot(inner[2, :], sharex=ax_modes)
        plt.setp(ax_modes.get_xticklabels(), visible=False)
        timeline(ax_modes, ax_state, tr, t_start - 0.25 * span, t_start + max(2.0, 2.5 * span), frames)
        frac = " / ".join(f"{s} {100 * m[s.lower()]:.0f} %" for s in STATE_NAMES)
        fig.text(0.06, outer[gi].get_position(fig).y1 + 0.004,
                 f"{g.name.upper()} (rtw label: {m['outcome']}) — {g.caption}\n"
                 f"over the analysis window: {frac}; f_w = {m['f_w']:.1f} Hz "
                 f"(new foot {m['f_w_newfoot']:.1f} Hz); speed {m['speed']:.2f} m/s; period {m['period']}; "
                 f"μ required {m['mu_required']:.2f}",
                 fontsize=9, va="bottom", fontweight="normal")
    handles = [Line2D([], [], color=ROD_COLOR[i], lw=3, label=f"rod {'abc'[i]}") for i in range(3)]
    handles += [
        Line2D([], [], color="#555555", lw=1, label="string"),
        Line2D([], [], marker="o", color="black", ls="none", label="stick (foot pinned)"),
        Line2D([], [], marker="D", color="black", markerfacecolor="white", ls="none", label="slide"),
        Patch(facecolor="#888888", label="timeline: stick"),
        Patch(facecolor="#cccccc", hatch="////", label="timeline: slide (blank: free)"),
    ]
    fig.legend(handles=handles, loc="upper center", ncol=8, fontsize=8.5, frameon=False, bbox_to_anchor=(0.5, 1.0))
    fig.text(0.5, 0.004,
             f"rtw-scan simulate … --config configs/variants/VARIANT.toml --set trace_dt={TRACE_DT} --trace; "
             f"frames: {nframes} snapshots over two steps after the first touchdown past 3/4 of the run, "
             "drawn in the world with the slope at its angle φ; timelines: yellow span and dotted lines = the frames",
             ha="center", va="bottom", fontsize=7.5, color="#444444")
    return save(fig, out, "gait-gallery")


# ------------------------------------------------------------- walk animation

# The README's animated gait: small enough to embed (≈ 1 MB), long enough for several steps.
WALK_GIF = dict(fps=20, speed=1.0, duration=4.0, width=480)


def walk_gif(binary: Path, data_dir: Path, out: Path) -> Path:
    """The Fig. 7(a) walk (the gallery's walk run) as an animated GIF, from its
    first steady touchdown (as the gallery's frames)."""
    m, tr = simulate(binary, WALK, data_dir / "trace-walk.parquet")
    checked(tr, m)
    start = steady_touchdown(tr, m)
    duration = min(WALK_GIF["duration"], float(tr.t[-1]) - start)
    anim = animate(tr, fps=WALK_GIF["fps"], speed=WALK_GIF["speed"], start=start, duration=duration,
                   width=WALK_GIF["width"])
    path = out / "walk.gif"
    anim.save(path)
    print(f"figures: wrote {path.relative_to(ROOT) if path.is_relative_to(ROOT) else path} "
          f"({anim.frame_count} frames, {path.stat().st_size / 1e6:.2f} MB)")
    return path


# ----------------------------------------------------------------------- main


FIGURES = ["fig-s2", "fig-s3", "fig-s4", "failure-rate", "gait-gallery", "walk-gif"]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", type=Path, default=ROOT / "target/release/rtw-scan", help="the rtw-scan binary")
    ap.add_argument("--results", type=Path, default=ROOT / "results", help="where the scans are")
    ap.add_argument("--out", type=Path, default=ROOT / "results/figures", help="where the PNGs go")
    ap.add_argument("--only", nargs="*", choices=FIGURES, help="make only these figures")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    data = a.out / "data"
    data.mkdir(exist_ok=True)
    want = set(a.only or FIGURES)
    plt.rcParams.update({"font.size": 9.5, "axes.titlesize": 10})
    paper = Scan.read(a.results / "paper/samples.parquet") if want & {"fig-s4", "failure-rate", "gait-gallery"} else None
    if "fig-s2" in want:
        fig_s2(Scan.read(a.results / "fig-s2/samples.parquet"), a.out)
    if "fig-s3" in want:
        fig_s3(Scan.read(a.results / "fig-s3/samples.parquet"), a.out)
    if "fig-s4" in want:
        fig_s4(paper, a.bin, data, a.out)
    if "failure-rate" in want:
        failure_rates(paper, a.out)
    if "gait-gallery" in want:
        gait_gallery(a.bin, paper, data, a.out)
    if "walk-gif" in want:
        walk_gif(a.bin, data, a.out)


if __name__ == "__main__":
    main()
