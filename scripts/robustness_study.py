"""The robustness study's tables and figures (docs/robustness-study.md), from the
scans scripts/robustness_study.sh makes: the (φ, f_n) map around Fig. 7(a)
and the paper scan, every stable gait with Floquet max |μ|, the gait
sensitivity norm, step_down_max, step_down_h50, the Monte Carlo steps to
fall and the mean first-passage time (MFPT).

The same scans with the rough slope drawn from other terrain seeds, in
OUT/seed*/map and OUT/seed*/paper (only their MFPT and steps to fall are
read), give each statistic of the MFPT at each draw and its spread.

Writes OUT/summary.md (every number docs/robustness-study.md quotes from the
study), OUT/map-mfpt.png, OUT/map.png and OUT/paper.png.

    .venv/bin/python scripts/robustness_study.py results/robustness [--times "NAME=TEXT;..."]
"""

from __future__ import annotations

import argparse
import copy
import tomllib
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyarrow as pa  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402
from scipy import stats  # noqa: E402

from robustness_stats import BOOTSTRAP, SEED, somers_d_ci, spearman, spearman_ci, tobit  # noqa: E402

from rtwscripts.labels import STABLE  # noqa: E402
# The cheap measures set against the MFPT, in the order of the tables.
MEASURES = [
    ("floquet_max", "Floquet max \\|μ\\|"),
    ("gsn", "GSN"),
    ("step_down_max", "step_down_max (m)"),
    ("step_down_h50", "step_down_h50 (m)"),
]
INPUTS = [("rho", "ρ (kg/m)"), ("alpha", "α"), ("fn", "f_n (Hz)"), ("zeta", "ζ"), ("phi", "φ (rad)")]
TOP = 10
FIG7A = {"phi": 0.15, "fn": 3.269}
# The columns that depend on the draw of the rough slope (terrain.seed);
# the other measures are taken on flat ground or a step.
DRAWN = ("mfpt", "mfpt_lo", "mfpt_hi", "fall_rate", "steps_to_fall", "steps_to_fall_censored")
HOW = (
    "`./scripts/robustness_study.sh` (the scans and this page) or "
    "`./scripts/robustness_study.sh --analyse-only` (this page from the committed scans)"
)


class Scan:
    """One scan's rows (every column as floats, `outcome` as strings) and its
    stable gaits."""

    def __init__(self, path: Path):
        # An interrupted scan has only its finished chunks (rtw-scan run
        # --resume finishes it): they are read as what they are, the
        # samples done so far.
        files = [path] if path.exists() else sorted((path.parent / ".partial").glob("chunk-*.parquet"))
        if not files:
            raise SystemExit(f"{path}: no scan (and no finished chunks in {path.parent / '.partial'})")
        t = pa.concat_tables([pq.read_table(f) for f in files])
        self.total = t.num_rows
        self.partial = not path.exists()
        meta = pq.read_metadata(files[0]).metadata
        self.config = tomllib.loads(meta[b"rtw.config"].decode())
        self.variant = meta[b"rtw.variant"].decode()
        self.outcome = np.array(t.column("outcome").to_pylist(), dtype=object)
        self.cols = {}
        for c in t.column_names:
            if c in ("outcome", "failure", "message", "start"):
                continue
            self.cols[c] = np.array([np.nan if v is None else float(v) for v in t.column(c).to_pylist()])
        self.stable = np.isin(self.outcome, STABLE)

    def s(self, col: str) -> np.ndarray:
        """A column over the stable gaits."""
        return self.cols[col][self.stable]

    def labels(self) -> np.ndarray:
        return self.outcome[self.stable]

    def open_above(self) -> np.ndarray:
        """Stable gaits whose MFPT interval is open above (mfpt_hi = ∞)."""
        return np.isfinite(self.s("mfpt")) & np.isinf(self.s("mfpt_hi"))

    def no_fall(self) -> np.ndarray:
        """Stable gaits whose estimator counted no fall in any batch: fall_rate
        0, mfpt = mfpt_hi = ∞, and mfpt_lo the lower bound the count supports."""
        return np.isinf(self.s("mfpt"))

    def censored_mfpt(self) -> tuple[np.ndarray, np.ndarray]:
        """The MFPT for a censoring-aware model, and where it is censored: an
        interval open above, and a gait with no fall counted, are
        right-censored at mfpt_lo, the lower bound the count supports."""
        m = self.s("mfpt")
        cens = self.open_above() | self.no_fall()
        y = np.where(cens, self.s("mfpt_lo"), m)
        return y, cens


def setting(scan: Scan, key: str, default: str) -> str:
    """A robustness key as the scan ran it (its stored config), or the
    library default when the config leaves it out."""
    sim = scan.config.get("simulation", {})
    table, name = key.split(".")
    v = sim.get(table, {}).get(name)
    return f"{v}" if v is not None else f"{default} (default)"


def fmt_mfpt(m: float, lo: float, hi: float) -> str:
    h = "∞" if np.isinf(hi) else f"{hi:.3g}"
    return f"{m:.3g} [{lo:.3g}, {h}]"


def undefined_table(scan: Scan) -> list[str]:
    n = int(scan.stable.sum())
    out = ["| measure | defined | undefined (null) |", "|---|---|---|"]
    m = scan.s("mfpt")
    fin, nof = np.isfinite(m), scan.no_fall()
    out.append(
        f"| MFPT | {fin.sum()} finite ({scan.open_above().sum()} of them with mfpt_hi = ∞, the interval open "
        f"above); {nof.sum()} with no fall seen (fall_rate 0, mfpt = ∞) | {n - fin.sum() - nof.sum()} |"
    )
    for col, name in MEASURES + [("steps_to_fall", "steps_to_fall")]:
        d = np.isfinite(scan.s(col)).sum()
        out.append(f"| {name} | {d} | {n - d} |")
    return out


# The fewest gaits a rank correlation is taken over, and the fewest
# observed (uncensored) MFPTs the censored model is fitted to.
MIN_GAITS = 3


def fmt_ci(r: float, lo: float, hi: float) -> str:
    """A correlation and its interval; a dash where too few gaits define it
    (fewer than three, or no spread in a rank)."""
    if not np.isfinite(r):
        return "—"
    if not (np.isfinite(lo) and np.isfinite(hi)):
        return f"{r:+.2f}"
    return f"{r:+.2f} [{lo:+.2f}, {hi:+.2f}]"


def rho_ci(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """Spearman's ρ with its interval, undefined (nan) below three gaits."""
    return spearman_ci(x, y) if len(x) >= MIN_GAITS else (np.nan, np.nan, np.nan)


def d_ci(x: np.ndarray, y: np.ndarray, cens: np.ndarray) -> tuple[float, float, float]:
    """Somers' D with its interval, undefined (nan) below three gaits or
    with none uncensored (no pair is comparable)."""
    return somers_d_ci(x, y, cens) if len(x) >= MIN_GAITS and (~cens).any() else (np.nan, np.nan, np.nan)


def common(scan: Scan, finite: bool = True) -> np.ndarray:
    """The stable gaits where every measure is defined and the MFPT is
    finite (or, with `finite` false, also ∞: no fall seen)."""
    ok = np.isfinite(scan.s("mfpt")) if finite else ~np.isnan(scan.s("mfpt"))
    for col, _ in MEASURES:
        ok &= np.isfinite(scan.s(col))
    return ok


def censored_common(scan: Scan) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The gaits of the censored statistics (every measure defined, the
    MFPT finite or no fall seen), and their MFPT and censoring there."""
    ok = common(scan, finite=False)
    yc, cens = (v[ok] for v in scan.censored_mfpt())
    return ok, yc, cens


def correlation_table(scan: Scan) -> list[str]:
    ok = common(scan)
    y = scan.s("mfpt")[ok]
    okc, yc, cens = censored_common(scan)
    out = [
        f"Spearman's ρ on the {ok.sum()} gaits where every measure is defined and the MFPT finite "
        f"({scan.open_above()[ok].sum()} of them open above, ranked by their point estimate); Somers' D on "
        f"those and the {scan.no_fall()[okc].sum()} with every measure defined and no fall seen "
        f"({okc.sum()} gaits, {cens.sum()} censored):",
        "",
        f"| measure | Spearman ρ with MFPT [95 %] ({ok.sum()} gaits) | Somers' D, censored [95 %] ({okc.sum()} gaits) | "
        "Spearman ρ where the measure alone is defined and the MFPT finite [95 %] (gaits) |",
        "|---|---|---|---|",
    ]
    for col, name in MEASURES + [("steps_to_fall", "steps_to_fall (Monte Carlo, censored at max_steps)")]:
        own = np.isfinite(scan.s(col)) & np.isfinite(scan.s("mfpt"))
        out.append(
            f"| {name} | {fmt_ci(*rho_ci(scan.s(col)[ok], y))} | {fmt_ci(*d_ci(scan.s(col)[okc], yc, cens))} | "
            f"{fmt_ci(*rho_ci(scan.s(col)[own], scan.s('mfpt')[own]))} ({own.sum()}) |"
        )
    return out


def tobit_table(scan: Scan) -> list[str]:
    """log10 MFPT on each measure alone and on all four, right-censored at
    mfpt_lo where the interval is open above."""
    ok, yc, cens = censored_common(scan)
    y = np.log10(yc)
    if (~cens).sum() < MIN_GAITS:
        # With (almost) every gait censored the likelihood has no maximum:
        # any slope fits gaits that are only known to walk beyond a bound.
        return [
            f"{ok.sum()} gaits (as Somers' D), {cens.sum()} right-censored: too few MFPTs are observed for the "
            f"model (it needs at least {MIN_GAITS} uncensored), so it is not fitted."
        ]
    out = [
        f"{ok.sum()} gaits (as Somers' D), {cens.sum()} right-censored:",
        "",
        "| model | slope (decades of MFPT per SD of the measure's normal score) [95 %] | "
        "residual SD (decades) | likelihood ratio χ² (df), p |",
        "|---|---|---|---|",
    ]
    for col, name in MEASURES:
        f = tobit([scan.s(col)[ok]], y, cens)
        out.append(
            f"| {name} alone | {f['beta'][0]:+.3f} [{f['lo'][0]:+.3f}, {f['hi'][0]:+.3f}] | "
            f"{f['sigma']:.3f} | {f['lr']:.2f} (1), {f['p']:.3g} |"
        )
    f = tobit([scan.s(c)[ok] for c, _ in MEASURES], y, cens)
    slopes = "; ".join(
        f"{name} {b:+.3f} [{lo:+.3f}, {hi:+.3f}]" for (_, name), b, lo, hi in zip(MEASURES, f["beta"], f["lo"], f["hi"])
    )
    out.append(f"| all four | {slopes} | {f['sigma']:.3f} | {f['lr']:.2f} ({len(MEASURES)}), {f['p']:.3g} |")
    if cens.mean() > 0.8:
        out += [
            "",
            f"{cens.mean():.0%} of these gaits are censored: the likelihood hardly bounds the MFPT from above, "
            "the slopes' intervals are wide, and in the joint model the two step-down measures (often equal) "
            "trade off against each other up to the fit's bounds (±20 decades).",
        ]
    return out


def step_down_line(scan: Scan) -> list[str]:
    """step_down_max over the stable gaits, as docs/robustness-step-down.md quotes it."""
    v, lab = scan.s("step_down_max"), scan.labels()
    ok = np.isfinite(v)
    cap = 16 * float(scan.config["params"]["length"])
    by = ", ".join(f"{g}s {np.median(v[ok & (lab == g)]):.2f} m" for g in STABLE if (ok & (lab == g)).any())
    return [
        f"step_down_max over these {ok.sum()} stable gaits: median {np.median(v[ok]):.2f} m ({by}), "
        f"10th percentile {np.percentile(v[ok], 10):.2f} m; {(v[ok] >= cap - 1e-9).sum()} at the 16 L cap "
        f"({cap:.1f} m); step_down_h50 equals step_down_max for {(scan.s('step_down_h50')[ok] == v[ok]).sum()}.",
    ]


def inputs_table(scan: Scan) -> list[str]:
    """Which input moves the MFPT: Spearman over every stable gait with an MFPT."""
    ok = np.isfinite(scan.s("mfpt"))
    out = ["| input | Spearman ρ with MFPT [95 %] |", "|---|---|"]
    for col, name in INPUTS:
        if np.ptp(scan.s(col)) == 0:
            continue
        out.append(f"| {name} | {fmt_ci(*rho_ci(scan.s(col)[ok], scan.s('mfpt')[ok]))} |")
    return out


def by_gait(scan: Scan) -> list[str]:
    out = [
        "| gait | gaits | MFPT finite | median MFPT | 10–90 % | open above | no fall seen | median fall_rate |",
        "|---|---|---|---|---|---|---|---|",
    ]
    lab, m, fr, op = scan.labels(), scan.s("mfpt"), scan.s("fall_rate"), scan.open_above()
    for g in STABLE:
        k = lab == g
        d = k & np.isfinite(m)
        if not k.any():
            continue
        if d.any():
            p10, p50, p90 = np.percentile(m[d], [10, 50, 90])
            frm = np.nanmedian(fr[d])
            out.append(
                f"| {g} | {k.sum()} | {d.sum()} | {p50:.3g} | {p10:.3g}–{p90:.3g} | {op[k].sum()} | "
                f"{scan.no_fall()[k].sum()} | {frm:.3g} |"
            )
        else:
            out.append(f"| {g} | {k.sum()} | 0 | — | — | 0 | {scan.no_fall()[k].sum()} | — |")
    return out


def no_fall_lines(scan: Scan) -> list[str]:
    """The gaits with no fall counted, against the Monte Carlo."""
    nof = scan.no_fall()
    if not nof.any():
        return ["No gait has fall_rate 0 (no fall counted)."]
    stf, cen = scan.s("steps_to_fall")[nof], scan.s("steps_to_fall_censored")[nof]
    trials = float(setting(scan, "robustness.trials", "20").split()[0])
    fell = cen < trials
    return [
        f"No fall was counted for {nof.sum()} stable gaits (fall_rate 0, mfpt = ∞; mfpt_lo, the lower bound "
        f"the count supports, median {np.median(scan.s('mfpt_lo')[nof]):.0f} steps). The Monte Carlo "
        f"saw at least one of its trials fall for {fell.sum()} of them (median steps_to_fall "
        f"{np.median(stf):.1f}, {np.median(trials - cen):.0f} of {trials:.0f} trials falling within "
        f"max_steps at the median): the Monte Carlo counts falls from the first step, the estimator's count "
        "only after its 60 steps of burn-in. The censored model takes them as at least mfpt_lo; Spearman's ρ "
        "and the ten below leave them out.",
    ]


def top_table(scan: Scan) -> list[str]:
    """The designs with the largest lower end of the MFPT's interval: what
    the runs support (a gait with no fall counted has only that bound)."""
    lo = scan.s("mfpt_lo")
    order = np.argsort(-np.where(np.isfinite(lo), lo, -np.inf), kind="mergesort")[:TOP]
    nof = scan.no_fall()
    one = np.isfinite(scan.s("fall_rate")) & (scan.s("fall_rate") > 0) & ~np.isfinite(scan.s("mfpt_hi"))
    out = [
        f"By `mfpt_lo`, ties in sample order: {nof.sum()} gaits had no fall counted and {one.sum()} more an "
        "interval open above, so these ten are not ordered among them by the estimator: its count of "
        "walker-steps (docs/robustness.md) supports MFPTs up to a few thousand steps.",
        "",
        "| sample | ρ | α | f_n | ζ | φ | gait | MFPT [95 %] | fall_rate | steps_to_fall | "
        "Floquet max \\|μ\\| | GSN | step_down_max | step_down_h50 |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for i in order:
        v = {c: scan.s(c)[i] for c in scan.cols}
        stf = f"{v['steps_to_fall']:.1f}" + (" (≥)" if v["steps_to_fall_censored"] > 0 else "")
        out.append(
            f"| {v['sample_id']:.0f} | {v['rho']:.3f} | {v['alpha']:.3f} | {v['fn']:.3f} | {v['zeta']:.4f} | "
            f"{v['phi']:.4f} | {scan.labels()[i]} | {fmt_mfpt(v['mfpt'], v['mfpt_lo'], v['mfpt_hi'])} | "
            f"{v['fall_rate']:.3g} | {stf} | {v['floquet_max']:.3f} | {v['gsn']:.3g} | "
            f"{v['step_down_max']:.3f} | {v['step_down_h50']:.3f} |"
        )
    return out


def apart_table(scan: Scan) -> list[str]:
    """The designs with no fall counted (the most robust the estimator can
    tell) against the stable gaits with a finite MFPT: inputs and measures,
    two-sided Mann–Whitney U."""
    top = scan.no_fall()
    rest = np.isfinite(scan.s("mfpt"))
    n_top = int(top.sum())
    out = [
        f"| | no fall counted ({n_top}): median [min, max] | stable gaits with a finite MFPT ({rest.sum()}): "
        "median [25–75 %] | Mann–Whitney p |",
        "|---|---|---|---|",
    ]
    for col, name in INPUTS + MEASURES:
        a, b = scan.s(col)[top], scan.s(col)[rest]
        a, b = a[np.isfinite(a)], b[np.isfinite(b)]
        if len(a) == 0 or len(b) == 0:
            out.append(f"| {name} | — ({len(a)} defined) | — | — |")
            continue
        p = stats.mannwhitneyu(a, b, alternative="two-sided").pvalue
        q1, q2, q3 = np.percentile(b, [25, 50, 75])
        na = f" ({len(a)} defined)" if len(a) < n_top else ""
        out.append(
            f"| {name} | {np.median(a):.3g} [{a.min():.3g}, {a.max():.3g}]{na} | {q2:.3g} [{q1:.3g}–{q3:.3g}] | {p:.2g} |"
        )
    lab = scan.labels()
    counts = ", ".join(f"{g} {int((lab[top] == g).sum())}" for g in STABLE)
    rest_counts = ", ".join(f"{g} {int((lab[rest] == g).sum())}" for g in STABLE)
    out += ["", f"Gaits: no fall counted {counts}; with a finite MFPT {rest_counts}."]
    return out


def map_mfpt_figure(scan: Scan, png: Path) -> None:
    phi, fn, m = scan.cols["phi"], scan.cols["fn"], scan.cols["mfpt"]
    hi = scan.cols["mfpt_hi"]
    ok = scan.stable & np.isfinite(m)
    fig, ax = plt.subplots(figsize=(6.6, 6.0))
    nof = scan.stable & np.isinf(m)
    ax.scatter(phi[~ok & ~nof], fn[~ok & ~nof], s=260, marker="s", color="0.85", label="not a stable gait")
    ax.scatter(phi[nof], fn[nof], s=260, marker="s", color="white", edgecolors="k",
               label="no fall seen (fall_rate 0, mfpt = ∞)")
    ax.scatter(phi[nof], fn[nof], s=40, marker="x", color="k")
    sc = ax.scatter(phi[ok], fn[ok], c=np.log10(m[ok]), s=260, marker="s", cmap="viridis")
    op = ok & np.isinf(hi)
    # White on the colour map; the legend, on white, shows it in black.
    ax.scatter(phi[op], fn[op], s=60, marker="^", facecolors="none", edgecolors="white", linewidths=1.2)
    ax.plot([], [], marker="^", ms=8, mfc="none", mec="k", ls="none", label="interval open above (mfpt_hi = ∞)")
    ax.plot(FIG7A["phi"], FIG7A["fn"], marker="*", color="red", ms=14, ls="none", label="Fig. 7(a)")
    fig.colorbar(sc, ax=ax, label="log10 MFPT (steps)")
    ax.set_xlabel("slope φ (rad)")
    ax.set_ylabel("f_n (Hz)")
    sigma = setting(scan, "robustness.sigma", "0.01")
    ax.set_title(f"MFPT around Fig. 7(a) (L 0.8, ρ 2.5, α 0.125, ζ 0.0514), σ = {sigma.split()[0]} m", fontsize=9)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def map_figure(scan: Scan, png: Path) -> None:
    phi, fn = scan.cols["phi"], scan.cols["fn"]
    panels = MEASURES + [("steps_to_fall", "steps_to_fall")]
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.6))
    axes = axes.ravel()
    for k, name in enumerate(sorted(set(scan.outcome))):
        sel = scan.outcome == name
        axes[0].scatter(phi[sel], fn[sel], s=60, marker="s", label=name, color=f"C{k}")
    axes[0].set_title("gait")
    axes[0].legend(fontsize=7)
    for ax, (col, name) in zip(axes[1:], panels):
        v = scan.cols[col]
        ok = scan.stable & np.isfinite(v)
        ax.scatter(phi[~ok], fn[~ok], s=60, marker="s", color="0.85")
        sc = ax.scatter(phi[ok], fn[ok], c=v[ok], s=60, marker="s", cmap="viridis")
        fig.colorbar(sc, ax=ax)
        ax.set_title(name.replace("\\", ""))
    for ax in axes:
        ax.set_xlabel("slope φ (rad)")
        ax.set_ylabel("f_n (Hz)")
    fig.suptitle("The cheap measures around Fig. 7(a); grey: not a stable gait, or the measure undefined")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def paper_figure(scan: Scan, png: Path) -> None:
    fig, axes = plt.subplots(1, len(MEASURES), figsize=(4.4 * len(MEASURES), 3.9))
    m, lo, op = scan.s("mfpt"), scan.s("mfpt_lo"), scan.open_above()
    lab = scan.labels()
    for ax, (col, name) in zip(axes, MEASURES):
        x = scan.s(col)
        for k, g in enumerate(STABLE):
            closed = (lab == g) & np.isfinite(x) & np.isfinite(m) & ~op
            opened = (lab == g) & np.isfinite(x) & op
            ax.scatter(x[closed], m[closed], s=8, alpha=0.6, color=f"C{k}", label=g)
            ax.scatter(x[opened], lo[opened], s=14, alpha=0.6, color=f"C{k}", marker="^")
        if col in ("step_down_max", "step_down_h50", "gsn"):
            ax.set_xscale("symlog", linthresh=0.01)
        ax.set_yscale("log")
        ax.set_xlabel(name.replace("\\", ""))
        ax.set_ylabel("MFPT (steps); ▲ open above, at mfpt_lo")
        ax.legend(fontsize=7)
    fig.suptitle("The paper scan's stable gaits: each cheap measure against the MFPT")
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def terrain_seed(scan: Scan) -> int:
    return int(scan.config.get("simulation", {}).get("terrain", {}).get("seed", 0))


def redrawn(base: Scan, other: Scan, where: Path) -> Scan:
    """`base` with the drawn columns of `other`: the same scan with the rough
    slope drawn from another terrain.seed, whose flat gaits are base's."""
    same = np.array_equal(base.cols["sample_id"], other.cols["sample_id"]) and np.array_equal(
        base.outcome, other.outcome
    )
    if other.partial or not same:
        raise SystemExit(f"{where}: not the same finished samples and gaits as the scan at terrain.seed 0")
    s = copy.copy(base)
    s.cols = {**base.cols, **{c: other.cols[c] for c in DRAWN}}
    return s


def mean_sd(v: list[float]) -> str:
    v = np.array([x for x in v if np.isfinite(x)])
    if len(v) < 2:
        return "—"
    return f"{v.mean():+.2f} ± {v.std(ddof=1):.2f}"


def seeds_lines(short: str, draws: list[tuple[int, Scan]]) -> list[str]:
    """The study's statistics on the rough slope drawn from each terrain
    seed, and their spread over the seeds: how far the answer moves with
    the draw of the ground."""
    k = len(draws)
    head = " | ".join(f"seed {s}" for s, _ in draws)
    rule = "|---|" + "---|" * (k + 1)
    rows = []
    for s, sc in draws:
        m = sc.s("mfpt")
        rows.append(
            f"{np.isfinite(m).sum()} finite ({sc.open_above().sum()} open above), {sc.no_fall().sum()} no fall"
        )
    out = [
        f"### {short}: over terrain seeds",
        "",
        f"The MFPT and the Monte Carlo steps to fall on the rough slope drawn from each of {k} terrain seeds "
        "(`--set terrain.seed=S`; the other measures do not depend on the draw): each statistic at each "
        "seed with its bootstrap interval over the gaits (and how many gaits), and the mean ± SD of the "
        f"{k} point estimates, the spread that comes from the draw of the ground.",
        "",
        f"| | {head} |",
        "|---|" + "---|" * k,
        f"| MFPT (stable gaits) | {' | '.join(rows)} |",
    ]

    def table(title: str, stat, rows=MEASURES + [("steps_to_fall", "steps_to_fall")]) -> list[str]:
        """One statistic of each measure at each seed, and its spread; a
        sentence instead where no seed defines it."""
        body, defined = [], False
        for col, name in rows:
            vals, pts, gaits = zip(*(stat(sc, col) for _, sc in draws))
            defined |= bool(np.isfinite(pts).any())
            cells = " | ".join(f"{v} ({g})" for v, g in zip(vals, gaits))
            body.append(f"| {name} | {cells} | {mean_sd(list(pts))} |")
        if not defined:
            at = "; ".join(f"seed {s}: {g}" for (s, _), g in zip(draws, gaits))
            return ["", f"{title}: undefined at every seed ({at})."]
        return ["", f"| {title} | {head} | mean ± SD |", rule, *body]

    # Each statistic of a measure at a draw: (its cell, its point estimate,
    # the gaits it is taken over).
    def rho(sc: Scan, col: str) -> tuple[str, float, str]:
        ok = common(sc)
        r = rho_ci(sc.s(col)[ok], sc.s("mfpt")[ok])
        return fmt_ci(*r), r[0], f"{ok.sum()} gaits"

    def somers(sc: Scan, col: str) -> tuple[str, float, str]:
        ok, yc, cens = censored_common(sc)
        r = d_ci(sc.s(col)[ok], yc, cens)
        return fmt_ci(*r), r[0], f"{ok.sum()} gaits, {cens.sum()} censored"

    def tobit_slope(sc: Scan, col: str) -> tuple[str, float, str]:
        ok, yc, cens = censored_common(sc)
        gaits = f"{ok.sum()} gaits, {cens.sum()} censored"
        if (~cens).sum() < MIN_GAITS:
            return "—", np.nan, gaits
        f = tobit([sc.s(col)[ok]], np.log10(yc), cens)
        return f"{f['beta'][0]:+.2f} [{f['lo'][0]:+.2f}, {f['hi'][0]:+.2f}], p {f['p']:.2g}", f["beta"][0], gaits

    out += table("Spearman ρ with MFPT, every measure defined and the MFPT finite", rho)
    out += table("Somers' D, censored, every measure defined", somers)
    out += table("Tobit slope alone (decades of MFPT per SD), every measure defined", tobit_slope, MEASURES)
    base, s0 = draws[0][1], draws[0][0]
    out += [
        "",
        f"| the same gait on two draws | Spearman ρ of the MFPTs (gaits finite at both) | inside seed {s0}'s "
        "interval | no fall seen at both or at neither (stable gaits) |",
        "|---|---|---|---|",
    ]
    for s, sc in draws[1:]:
        a, b = base.s("mfpt"), sc.s("mfpt")
        both = np.isfinite(a) & np.isfinite(b)
        inside = both & (b >= base.s("mfpt_lo")) & (b <= base.s("mfpt_hi"))
        nof = base.no_fall() == sc.no_fall()
        r = spearman(a[both], b[both]) if both.sum() >= MIN_GAITS else np.nan
        out.append(
            f"| seed {s} against seed {s0} | {fmt_ci(r, np.nan, np.nan)} ({both.sum()}) | {inside.sum()} of "
            f"{both.sum()} | {nof.sum()} of {len(a)} |"
        )
    return out


def section(scan: Scan, title: str, short: str, top: bool, draws: list[tuple[int, Scan]]) -> list[str]:
    n = int(scan.stable.sum())
    ids = scan.cols["sample_id"]
    lines = [f"## {title}: {n} stable gaits of {scan.total}", ""]
    if scan.partial:
        lines += [
            f"**Interrupted scan**: these are its first {scan.total} of {scan.config['samples']} samples "
            f"(sample_id {ids.min():.0f}–{ids.max():.0f}, the finished chunks in .partial/; the samples are "
            "independent uniform draws, so the first ones are a random subsample of the same design space). "
            "`rtw-scan run configs/paper.toml --out results/robustness/paper --resume` with the study's "
            "`--set` options finishes it.",
            "",
        ]
    lines += [
        f"### {short}: where each measure is defined",
        "",
        "Stable gaits only; a measure is null where rtw cannot compute it.",
        "",
        *undefined_table(scan),
        "",
        f"### {short}: rank correlation with the MFPT",
        "",
        *correlation_table(scan),
        "",
        f"### {short}: censored regression of log10 MFPT (Tobit)",
        "",
        *tobit_table(scan),
        "",
        f"### {short}: by gait",
        "",
        *by_gait(scan),
        "",
        *step_down_line(scan),
        "",
        *no_fall_lines(scan),
        "",
        f"### {short}: the inputs against the MFPT (every stable gait with a finite MFPT)",
        "",
        *inputs_table(scan),
    ]
    if len(draws) > 1:
        lines += ["", *seeds_lines(short, draws)]
    if top:
        lines += ["", f"### {short}: the {TOP} designs with the largest lower end of the MFPT", "", *top_table(scan), ""]
        lines += [f"### {short}: what sets the designs with no fall counted apart", ""]
        lines += apart_table(scan)
    return lines


def sigma_of(scan: Scan) -> float:
    """The roughness a scan's MFPT was taken at (m)."""
    return float(setting(scan, "robustness.sigma", "0.01").split()[0])


def roughness_name(sigma: float, seed: int) -> str:
    return f"{sigma * 100:g} cm" + (f" (terrain.seed {seed})" if seed else "")


def roughness_row(a: Scan, b: Scan) -> str:
    """How `a`'s MFPT ranks the gaits against `b`'s, on smoother (or other)
    ground: Spearman's ρ where both are finite, Somers' D with `b`
    right-censored, and how many of `a`'s 20 longest walkers saw no fall on
    `b`'s ground. A gait with no fall seen on `a`'s ground ranks by its
    mfpt_lo there."""
    xa = np.where(np.isfinite(a.s("mfpt")), a.s("mfpt"), a.s("mfpt_lo"))
    both = np.isfinite(a.s("mfpt")) & np.isfinite(b.s("mfpt"))
    yb, cens = b.censored_mfpt()
    top = np.argsort(-xa, kind="stable")[:20]
    nf = b.no_fall()
    return (
        f"{fmt_ci(*rho_ci(xa[both], b.s('mfpt')[both]))} ({both.sum()}) | "
        f"{fmt_ci(*d_ci(xa, yb, cens))} ({cens.sum()} of {len(yb)}) | "
        f"{nf[top].sum()} of 20 ({nf.sum()} of {len(nf)})"
    )


def roughness_page(base: Scan, rougher: list[Path], page: Path) -> None:
    """results/robustness/roughness.md: the paper scan's MFPT at each
    roughness of `rougher` (scans of configs/paper.toml with only the MFPT,
    robustness.sigma set) against the study's own scan (`base`, 1 cm): does
    the ranking on rough ground, where falls are counted, carry to the
    smoother ground where most gaits fall too seldom to count?"""
    levels = [(sigma_of(base), terrain_seed(base), base, "results/robustness/paper/")]
    for d in rougher:
        sc = Scan(d / "samples.parquet")
        same = np.array_equal(sc.cols["sample_id"], base.cols["sample_id"]) and np.array_equal(sc.outcome, base.outcome)
        if sc.partial or not same:
            raise SystemExit(f"{d}: not the same finished samples and gaits as the 1 cm paper scan")
        levels.append((sigma_of(sc), terrain_seed(sc), sc, f"results/robustness/roughness/{d.name}/"))
    levels.sort(key=lambda t: (-t[0], t[1]))
    out = [
        "# The MFPT across roughness: does the ranking on rough ground carry to smoother ground?",
        "",
        f"Every number on this page: {HOW}.",
        "",
        "The paper scan's stable gaits (configs/paper.toml, the default model; the same gaits in every scan, "
        "whose flat runs are the same) with the counted MFPT (`robustness.mfpt_method` \"counted\", the default) "
        "on the rough slope of terrain.seed 0 at each roughness: "
        + "; ".join(f"σ = {roughness_name(sig, seed)}: {where}" for sig, seed, _, where in levels)
        + ". The rougher scans are `rtw-scan run configs/paper.toml --set robustness.mfpt=true --set "
        "robustness.sigma=S` (and `--set terrain.seed=100` for the second draw); the 1 cm one is the "
        "robustness study's (summary.md). The scans on terrain.seed 0 walk the same standard-normal heights, "
        "scaled by σ, so part of their agreement is the shared ground; the row from the second draw at 5 cm "
        "has none, and the row between the two draws at 5 cm is the ranking's own noise floor there.",
        "",
        "A design search on rough ground (configs/design/robust.toml, 5 cm) ranks designs by an MFPT that "
        "counting can reach. Whether that ranking holds on the default 1 cm, where most gaits fall too seldom to "
        "count, is what this page measures. Somers' D treats an MFPT that is open above, or has no fall seen, "
        "as right-censored at mfpt_lo on the smoother ground; a gait with no fall seen on the rougher ground "
        "is ranked by its mfpt_lo there. The intervals are bootstrap percentiles over the gaits "
        "(scripts/robustness_stats.py).",
        "",
        "| σ | stable gaits | MFPT finite, interval closed | finite, open above | no fall seen | "
        "median MFPT of the finite (other gaits at each σ) |",
        "|---|---|---|---|---|---|",
    ]
    for sig, seed, sc, _ in levels:
        m = sc.s("mfpt")
        fin = np.isfinite(m)
        median = f"{np.median(m[fin]):.4g}" if fin.any() else "—"
        out.append(
            f"| {roughness_name(sig, seed)} | {sc.stable.sum()} | {(fin & ~sc.open_above()).sum()} | "
            f"{sc.open_above().sum()} | {sc.no_fall().sum()} | {median} |"
        )
    out += [
        "",
        "| rougher (or another draw) → smoother | Spearman ρ [95 %] (gaits finite at both) | Somers' D, smoother "
        "censored [95 %] (all stable gaits; censored) | of the rougher's 20 longest walkers: no fall seen on the "
        "smoother ground (of all gaits) |",
        "|---|---|---|---|",
    ]
    for i, (s1, e1, a, _) in enumerate(levels):
        for s2, e2, b, _ in levels[i + 1 :]:
            out.append(f"| {roughness_name(s1, e1)} → {roughness_name(s2, e2)} | {roughness_row(a, b)} |")
    page.write_text("\n".join(out) + "\n")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("out", type=Path)
    ap.add_argument("--times", default="", help="what the shell script timed, as NAME=TEXT;...")
    a = ap.parse_args()
    mp, pp = Scan(a.out / "map" / "samples.parquet"), Scan(a.out / "paper" / "samples.parquet")
    draws = {}
    for short, base in (("map", mp), ("paper", pp)):
        draws[short] = [(terrain_seed(base), base)]
        # The same scans with the rough slope drawn from other seeds, the
        # drawn columns only (scripts/robustness_study.sh: seed*/).
        for d in sorted(a.out.glob("seed*/"), key=lambda d: d.name):
            path = d / short / "samples.parquet"
            other = Scan(path)
            draws[short].append((terrain_seed(other), redrawn(base, other, path)))
    map_mfpt_figure(mp, a.out / "map-mfpt.png")
    map_figure(mp, a.out / "map.png")
    paper_figure(pp, a.out / "paper.png")
    sig = setting(pp, "robustness.sigma", "0.01")
    more = [s for s, _ in draws["paper"][1:]]
    redraws = (
        f" Both again on the rough slope drawn from terrain.seed {', '.join(map(str, more))} (results/robustness/"
        f"seed{more[0]}/ …), with `--set terrain.seed=S --set robustness.steps_to_fall=true --set "
        "robustness.mfpt=true`: the statistics of the MFPT with their spread over the draws."
        if more
        else ""
    )
    lines = [
        "# The robustness study",
        "",
        f"Every number on this page: {HOW}.",
        "",
        "The scans: `rtw-scan run configs/robustness-map.toml` and `rtw-scan run configs/paper.toml`, each with "
        "`--set limit_cycle=true --set robustness.step_down=true --set robustness.step_down_h50=true "
        "--set robustness.gsn=true --set robustness.steps_to_fall=true --set robustness.mfpt=true` "
        f"(results/robustness/map/, results/robustness/paper/). Roughness σ = {sig} m "
        f"(robustness.sigma), patches {setting(pp, 'terrain.patch', '0.8')} m, steps to fall over "
        f"{setting(pp, 'robustness.trials', '20')} trials censored at "
        f"{setting(pp, 'robustness.max_steps', '100')} steps. Model: `{pp.variant}`."
        + redraws,
        "",
        "Statistics (scripts/robustness_stats.py): Spearman's ρ with ties averaged, on the MFPT's point "
        "estimate; Somers' D = 2C − 1 from Harrell's concordance C, which treats an MFPT whose interval is "
        "open above as right-censored at mfpt_lo; the intervals are the 2.5–97.5 % percentiles of "
        f"{BOOTSTRAP} (ρ) or 300 (D) bootstrap resamples of the gaits (seed {SEED}). The censored regression "
        "is a Tobit model: log10 MFPT = β₀ + Σ βᵢ zᵢ + ε, ε ~ N(0, s²), a gait open above contributing "
        "P(log10 MFPT ≥ log10 mfpt_lo); zᵢ is the measure's van der Waerden normal score (unit SD), "
        "slopes with 200 bootstrap resamples, the likelihood ratio against the intercept alone.",
        "",
        *section(pp, "The paper scan (configs/paper.toml)", "Paper", top=True, draws=draws["paper"]),
        "",
        *section(
            mp, "The (φ, f_n) map around Fig. 7(a) (configs/robustness-map.toml)", "Map", top=False,
            draws=draws["map"],
        ),
    ]
    if a.times:
        lines += ["", "## Run times (this machine, as the script ran)", ""]
        lines += [f"- {k.replace('_', ' ')}: {v}" for k, v in (t.split("=", 1) for t in a.times.split(";"))]
    (a.out / "summary.md").write_text("\n".join(lines) + "\n")
    rougher = sorted((a.out / "roughness").glob("paper-*/"))
    if rougher:
        roughness_page(pp, rougher, a.out / "roughness.md")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
