"""The robustness study's tables and figures (docs/robustness.md), from the
scans scripts/robustness_study.sh makes: the (φ, f_n) map around Fig. 7(a)
and the paper scan's stable gaits, each with Floquet max |μ|, the largest
survivable step down, the gait sensitivity norm when rtw has it, and the
Monte Carlo steps to fall.

Writes OUT/summary.md (the correlation table, the most robust designs and
the run times), OUT/map.png and OUT/paper.png.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pyarrow.parquet as pq  # noqa: E402

STABLE = ("skip", "walk", "crawl")
# The measures correlated with the steps to fall, and how each reads.
MEASURES = [
    ("floquet_max", "Floquet max |μ|"),
    ("step_down_max", "largest step down (m)"),
    ("gsn", "gait sensitivity norm"),
]
BOOTSTRAP = 2000
SEED = 27


def ranks(x: np.ndarray) -> np.ndarray:
    """Ranks with ties averaged (the censored steps to fall tie at max_steps)."""
    order = np.argsort(x, kind="mergesort")
    r = np.empty(len(x))
    r[order] = np.arange(len(x), dtype=float)
    xs = x[order]
    i = 0
    while i < len(xs):
        j = i
        while j + 1 < len(xs) and xs[j + 1] == xs[i]:
            j += 1
        r[order[i : j + 1]] = 0.5 * (i + j)
        i = j + 1
    return r


def spearman(x: np.ndarray, y: np.ndarray) -> float:
    rx, ry = ranks(x), ranks(y)
    if rx.std() == 0 or ry.std() == 0:
        return float("nan")
    return float(np.corrcoef(rx, ry)[0, 1])


def spearman_ci(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """Spearman's ρ and its 95 % percentile bootstrap interval (pairs resampled)."""
    rng = np.random.default_rng(SEED)
    n = len(x)
    boot = []
    for _ in range(BOOTSTRAP):
        i = rng.integers(0, n, n)
        boot.append(spearman(x[i], y[i]))
    lo, hi = np.nanpercentile(boot, [2.5, 97.5])
    return spearman(x, y), float(lo), float(hi)


def stable_rows(path: Path) -> dict[str, np.ndarray]:
    t = pq.read_table(path)
    cols = {c: np.array(t.column(c).to_pylist(), dtype=object) for c in t.column_names}
    keep = np.isin(cols["outcome"], STABLE)
    return {c: v[keep] for c, v in cols.items()}


def floats(v: np.ndarray) -> np.ndarray:
    return np.array([np.nan if x is None else float(x) for x in v])


def correlations(rows: dict[str, np.ndarray]) -> list[str]:
    stf = floats(rows["steps_to_fall"])
    out = []
    for col, name in MEASURES:
        if col not in rows:
            out.append(f"| {name} | — | — | not in this build (`robustness.{col}` unknown to rtw) |")
            continue
        x = floats(rows[col])
        ok = np.isfinite(x) & np.isfinite(stf)
        r, lo, hi = spearman_ci(x[ok], stf[ok])
        out.append(f"| {name} | {r:+.2f} | [{lo:+.2f}, {hi:+.2f}] | {ok.sum()} |")
    return out


def map_figure(path: Path, png: Path) -> None:
    t = pq.read_table(path)
    phi = np.array(t.column("phi").to_pylist())
    fn = np.array(t.column("fn").to_pylist())
    label = np.array(t.column("outcome").to_pylist())
    stable = np.isin(label, STABLE)
    panels = [(c, n) for c, n in MEASURES if c in t.column_names] + [
        ("steps_to_fall", "mean steps to fall (σ = 1 cm)")
    ]
    fig, axes = plt.subplots(1, len(panels) + 1, figsize=(4.2 * (len(panels) + 1), 3.8))
    names = sorted(set(label))
    for k, name in enumerate(names):
        m = label == name
        axes[0].scatter(phi[m], fn[m], s=60, marker="s", label=name, color=f"C{k}")
    axes[0].set_title("gait")
    axes[0].legend(fontsize=7)
    for ax, (col, name) in zip(axes[1:], panels):
        v = floats(np.array(t.column(col).to_pylist(), dtype=object))
        ax.scatter(phi[~stable], fn[~stable], s=60, marker="s", color="0.85")
        sc = ax.scatter(phi[stable], fn[stable], c=v[stable], s=60, marker="s", cmap="viridis")
        fig.colorbar(sc, ax=ax)
        ax.set_title(name)
    for ax in axes:
        ax.set_xlabel("slope φ (rad)")
        ax.set_ylabel("f_n (Hz)")
    fig.suptitle("Robustness around Fig. 7(a) (L 0.8, ρ 2.5, α 0.125, ζ 0.0514); grey: not a stable gait")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def paper_figure(rows: dict[str, np.ndarray], png: Path) -> None:
    panels = [(c, n) for c, n in MEASURES if c in rows]
    fig, axes = plt.subplots(1, len(panels), figsize=(4.5 * len(panels), 3.8))
    stf = floats(rows["steps_to_fall"])
    for ax, (col, name) in zip(np.atleast_1d(axes), panels):
        x = floats(rows[col])
        for k, lab in enumerate(STABLE):
            m = rows["outcome"] == lab
            ax.scatter(x[m], stf[m], s=8, alpha=0.6, label=lab, color=f"C{k}")
        if col == "step_down_max":
            ax.set_xscale("log")
        ax.set_xlabel(name)
        ax.set_ylabel("mean steps to fall")
        ax.legend(fontsize=7)
    fig.suptitle("The paper scan's stable gaits: each measure against the Monte Carlo steps to fall")
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def top(rows: dict[str, np.ndarray], n: int = 5) -> list[str]:
    stf = floats(rows["steps_to_fall"])
    order = np.argsort(-stf, kind="mergesort")[:n]
    out = []
    for i in order:
        out.append(
            "| {:.3f} | {:.3f} | {:.3f} | {:.3f} | {:.4f} | {:.3f} | {} | {:.1f} [{:.1f}, {:.1f}]{} | {:.3f} |".format(
                *(float(rows[c][i]) for c in ("rho", "alpha", "fn", "zeta", "phi")),
                float(rows["floquet_max"][i]) if rows["floquet_max"][i] is not None else float("nan"),
                rows["outcome"][i],
                stf[i],
                float(rows["steps_to_fall_lo"][i]),
                float(rows["steps_to_fall_hi"][i]),
                " (≥, censored {:.0f})".format(float(rows["steps_to_fall_censored"][i]))
                if float(rows["steps_to_fall_censored"][i]) > 0
                else "",
                float(rows["step_down_max"][i]),
            )
        )
    return out


def by_label(rows: dict[str, np.ndarray]) -> list[str]:
    stf = floats(rows["steps_to_fall"])
    out = []
    for lab in STABLE:
        m = rows["outcome"] == lab
        if m.any():
            cens = floats(rows["steps_to_fall_censored"])[m]
            out.append(
                f"| {lab} | {m.sum()} | {np.median(stf[m]):.1f} | {np.mean(stf[m]):.1f} | {(cens > 0).mean():.0%} |"
            )
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("out", type=Path)
    ap.add_argument("--times", default="", help="what the shell script timed, as NAME=TEXT;...")
    a = ap.parse_args()
    mp, pp = a.out / "map" / "samples.parquet", a.out / "paper" / "samples.parquet"
    map_rows, paper_rows = stable_rows(mp), stable_rows(pp)
    map_figure(mp, a.out / "map.png")
    paper_figure(paper_rows, a.out / "paper.png")
    head = "| measure | Spearman ρ with steps to fall | 95 % bootstrap interval | gaits |\n|---|---|---|---|"
    lines = [
        "# The robustness study",
        "",
        "Made by `./scripts/robustness_study.sh` (docs/robustness.md). Steps to fall: "
        "`robustness.steps_to_fall` at its defaults (σ = 1 cm, 0.8 m patches, 20 trials, "
        "censored at 100 steps). Spearman's ρ with ties averaged; the interval is the "
        f"2.5–97.5 % percentile of {BOOTSTRAP} bootstrap resamples of the gaits (seed {SEED}).",
        "",
        f"## The (φ, f_n) map around Fig. 7(a): {len(map_rows['outcome'])} stable gaits of "
        f"{pq.read_metadata(mp).num_rows}",
        "",
        head,
        *correlations(map_rows),
        "",
        f"## The paper scan's stable gaits: {len(paper_rows['outcome'])} of "
        f"{pq.read_metadata(pp).num_rows} (all of them, no subsample)",
        "",
        head,
        *correlations(paper_rows),
        "",
        "By gait (a lower bound where any trial was censored):",
        "",
        "| gait | gaits | median steps to fall | mean | share with a censored trial |",
        "|---|---|---|---|---|",
        *by_label(paper_rows),
        "",
        "The five paper-scan gaits that walk longest on the rough slope:",
        "",
        "| ρ | α | f_n | ζ | φ | Floquet max |μ| | gait | steps to fall [95 %] | step down max (m) |",
        "|---|---|---|---|---|---|---|---|---|",
        *top(paper_rows),
        "",
        "The five of the map:",
        "",
        "| ρ | α | f_n | ζ | φ | Floquet max |μ| | gait | steps to fall [95 %] | step down max (m) |",
        "|---|---|---|---|---|---|---|---|---|",
        *top(map_rows),
    ]
    if a.times:
        lines += ["", "## Run times (this machine, as the script ran)", ""]
        lines += [f"- {k.replace('_', ' ')}: {v}" for k, v in (t.split("=", 1) for t in a.times.split(";"))]
    (a.out / "summary.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
