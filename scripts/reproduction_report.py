"""The side-by-side table of docs/reproduction.md (and the README): every number
of docs/model.md §8 (and the Fig. 7(a) walk), the paper's value beside rtw's with
its 95 % sampling interval, for the default model and the paper-faithful one.

Reads (all written by committed commands):
  results/paper, results/fig-s2, results/fig-s3      (rtw-scan run configs/<name>.toml)
  results/variants/literal/{paper,fig-s3,fig7a.json} (./scripts/variants.sh)
  results/variants/<default>/fig7a.json
  results/variants/summary.json                      (scripts/variants_report.py: the
                                                      default's shares over the study's seeds)
Writes results/reproduction.md and prints it.

Usage: python scripts/reproduction_report.py
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import polars as pl

from rtwscripts import DEFAULT_VARIANT, ROOT
from rtwscripts.labels import FAILED, STABLE
from rtwscripts.paper import PAPER, cluster_regions
from rtwscripts.stats import permutation_p, wilson



def scan(d: Path) -> pl.DataFrame:
    return pl.read_parquet(d / "samples.parquet").with_columns(pl.col("outcome").cast(pl.Utf8))


def pct(df: pl.DataFrame, outcomes: Sequence[str]) -> str:
    k = df.filter(pl.col("outcome").is_in(outcomes)).height
    lo, hi = wilson(np.array([k]), np.array([df.height]))
    return f"{100 * k / df.height:.1f} ({100 * lo[0]:.1f}–{100 * hi[0]:.1f})"


def over_seeds(share: dict | None) -> str:
    """A share as the mean ± standard error over the variant study's seeds,
    with the two-sample 95 % interval of its difference from the paper's."""
    if share is None:
        return "–"
    mean = f"{share['mean']:.1f} ± {share['se']:.1f}"
    if "paper" not in share:
        return mean
    lo, hi = share["paper"]["ci95"]
    return f"{mean} ({lo:+.1f} to {hi:+.1f})"


def default_seeds(res: Path) -> dict:
    """The default variant's multi-seed statistic from the variant study."""
    summ = json.loads((res / "variants" / "summary.json").read_text())
    v = next(v for v in summ["variants"] if v["variant"] == DEFAULT_VARIANT)
    return v["seeds"]


def fig7a(d: Path) -> str:
    f = json.loads((d / "fig7a.json").read_text())
    return f"{f['outcome']}: SLSP {100 * f['slsp']:.0f} / DLSP {100 * f['dlsp']:.0f} / NLSP {100 * f['nlsp']:.0f} %"


def s3(df: pl.DataFrame) -> str:
    walk = df.filter(pl.col("outcome") == "walk").height
    off = (df["slsp"].fill_null(0.0) * 100 - 50).abs()
    mid = df.filter((pl.col("phi") >= 0.1) & (pl.col("phi") <= 0.175))
    off_mid = (mid["slsp"].fill_null(0.0) * 100 - 50).abs().mean()
    return (
        f"walk at {walk} of {df.height} points; abs(SLSP − 50 %) mean {off.mean():.1f} pp "
        f"(φ 0.1–0.175: {off_mid:.1f} pp)"
    )


def s2(df: pl.DataFrame) -> str:
    st = df.filter(pl.col("outcome").is_in(STABLE))
    ratio = (st["f_w_newfoot"] / st["fn"]).to_numpy()
    near = int((np.abs(ratio - 1) <= 0.25).sum())
    return (
        f"{st.height} of {df.height} stable; f_w(new foot)/f_n median {np.median(ratio):.2f}, "
        f"range {ratio.min():.2f}–{ratio.max():.2f}; within ±25 % of f_n: {near}"
    )


def clusters(d: Path) -> str:
    summ = json.loads((d / "summary.json").read_text())
    cl = (summ.get("clusters") or {"clusters": []})["clusters"]
    regions = cluster_regions(cl)["regions"]
    return "; ".join(
        f"{r} (α {c['alpha']:.2f}, f_n {c['fn']:.2f}, φ {c['phi']:.3f}; {c['collapse']} collapse / {c['stall']} stall)"
        for c, r in zip(cl, regions)
    )


def independence(df: pl.DataFrame, col: str, lo: float, hi: float) -> str:
    failed = df["outcome"].is_in(FAILED).to_numpy().astype(float)
    edges = np.linspace(lo, hi, 9)
    bins = np.clip(np.digitize(df[col].to_numpy(), edges) - 1, 0, 7)
    stat, p = permutation_p(bins, failed, 8, 2000, 1)
    return f"χ² {stat:.1f}, p {p:.3f}" if p > 1.5 / 2001 else f"χ² {stat:.1f}, p < 0.001"


def share_of(row: str) -> str | None:
    """The outcome share a row of the table is about (`stable`, `skip`, …), if any."""
    return row.split(" %")[0].split(": ")[-1] if " %" in row else None


def main() -> None:
    res = ROOT / "results"
    paper, lit_paper = scan(res / "paper"), scan(res / "variants" / "literal" / "paper")
    fs3, lit_s3 = scan(res / "fig-s3"), scan(res / "variants" / "literal" / "fig-s3")
    fs2 = scan(res / "fig-s2")
    seeds = default_seeds(res)
    rows = [
        ("Fig. 7(a) gait (main article)", "walk, SLSP ≈ DLSP ≈ 50 %",
         fig7a(res / "variants" / DEFAULT_VARIANT), fig7a(res / "variants" / "literal")),
        ("Fig. S2: f_w of stable gaits, f_n 2–5 Hz", "close to f_n", s2(fs2), "–"),
        ("Fig. S3: φ 0.05–0.2, L 0.7/0.8/0.9", "walk, SLSP ≈ DLSP ≈ 50 %, same for each L", s3(fs3), s3(lit_s3)),
        ("stable % (1000 samples)", f"{PAPER['stable']}", pct(paper, STABLE), pct(lit_paper, STABLE)),
        ("skip %", f"{PAPER['skip']}", pct(paper, ["skip"]), pct(lit_paper, ["skip"])),
        ("walk %", f"{PAPER['walk']:g}", pct(paper, ["walk"]), pct(lit_paper, ["walk"])),
        ("crawl %", f"{PAPER['crawl']}", pct(paper, ["crawl"]), pct(lit_paper, ["crawl"])),
        ("failed: collapse %", "– (one cluster)", pct(paper, ["collapse"]), pct(lit_paper, ["collapse"])),
        ("failed: stall %", "– (other cluster)", pct(paper, ["stall"]), pct(lit_paper, ["stall"])),
        ("Fig. S4 failure clusters", "small α & low f_n (stiffness collapse); small φ (energy barrier)",
         clusters(res / "paper"), clusters(res / "variants" / "literal" / "paper")),
    ]
    for col, lo, hi, name in [("rho", 1.0, 5.0, "ρ"), ("zeta", 0.05, 0.1, "ζ"), ("alpha", 0.0, 0.4, "α"),
                              ("fn", 1.5, 5.0, "f_n"), ("phi", 0.05, 0.3, "φ")]:
        claim = "nearly independent" if col in ("rho", "zeta") else "–"
        rows.append((f"failure against {name} (8 bins, permutation test)", claim,
                     independence(paper, col, lo, hi), independence(lit_paper, col, lo, hi)))
    n_seeds = len(seeds["seeds"])
    by_seed = {"Fig. S4 failure clusters": f"both clusters on {seeds['both_clusters_seeds']} of {n_seeds} seeds"}
    lines = [
        "| number (docs/model.md §8) | paper | rtw, default model (95 % CI) "
        f"| rtw, default model over {n_seeds} seeds: mean ± SE (95 % interval of the difference from the paper) "
        "| rtw, paper-faithful `literal` (95 % CI) |",
        "|---|---|---|---|---|",
    ] + [
        f"| {a} | {b} | {c} | {by_seed.get(a) or over_seeds(seeds['share'].get(share_of(a)))} | {d} |"
        for a, b, c, d in rows
    ]
    text = "\n".join(lines) + "\n"
    (res / "reproduction.md").write_text(
        "# Reproduction: paper against rtw\n\nGenerated by `.venv/bin/python scripts/reproduction_report.py` "
        "from the committed results (see docs/reproduction.md).\n\n" + text
    )
    print(text)


if __name__ == "__main__":
    main()
