"""The design searches against Sobol designs at equal cost (docs/design.md).

For each config, method and seed, reads runs/design-bench/CONFIG-METHOD-SEED/
search.parquet (every evaluated design, in order, with the simulations it
cost), designs.parquet (the reported best, profiled again on the fine grid
and checked by direct simulation) and archive.parquet (the best design of
each cell of the archive), and takes
  - found: the best objective among the designs evaluated before the
    cumulative simulations pass the config's budget (the same count for
    every method), as the search's own profile gives it;
  - verified: the reported best design's objective on the fine grid;
  - infeasible: the share of evaluated designs with no objective (they fall);
  - cells: the archive's cells filled; QD-score: the sum of its elites'
    scores (normalised objectives), as the search wrote them.
Then, per method, the mean over seeds and the mean paired difference from
Sobol at the same seed (Sobol − method for phi_min, so that positive is
better for the method) with its paired t 95 % interval, and how many seeds
it is better at.

Writes results/design/bench.md and results/design/bench-seeds.csv.
Usage: python scripts/design_bench.py RUNS CONFIG [CONFIG ...]
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
from scipy import stats

ROOT = Path(__file__).resolve().parent.parent
METHODS = {
    "sobol": "Sobol designs (baseline)",
    "cmaes": "CMA-ES, fall model",
    "cmaes-nomodel": "CMA-ES, no fall model",
    "archive": "MAP-Elites archive, fall model",
    "archive-penalty": "MAP-Elites archive, falls as a bad value",
}


def budget_of(config: Path) -> int:
    return int(re.search(r"^budget = (\d+)", config.read_text(), re.M).group(1))


def objective_of(config: Path) -> str:
    return re.search(r'^objectives = \["(\w+)"', config.read_text(), re.M).group(1)


def one(run: Path, budget: int, objective: str) -> dict[str, float]:
    t = pq.read_table(run / "search.parquet").to_pydict()
    runs = np.cumsum(t["runs"])
    within = runs <= budget
    values = np.array([np.nan if v is None else v for v in t[objective]], dtype=float)
    feasible = np.array(t["feasible"]) & within
    sign = -1.0 if objective == "phi_min" else 1.0
    found = sign * np.nanmax(sign * values[feasible]) if feasible.any() else np.nan
    d = pq.read_table(run / "designs.parquet").to_pydict()
    a = pq.read_table(run / "archive.parquet").to_pydict()
    return {
        "found": found,
        "verified": d[objective][0] if d[objective] else np.nan,
        "infeasible": 1.0 - np.mean(np.array(t["feasible"])[within]),
        "designs": int(within.sum()),
        "cells": len(a["score"]),
        "qd": float(np.sum(a["score"])),
        # The learned fall probability of the designs drawn (none for Sobol,
        # which consults no model); with avoid = 1 the draws are unscreened.
        "p_fall": max((p for p, w in zip(t["p_fall"], within) if w and p is not None), default=np.nan),
        # The designs drawn, in order: two searches are the same search when these are.
        "drawn": [d for d, w in zip(zip(t["rho"], t["alpha"], t["fn"], t["zeta"]), within) if w],
    }


def pmax(p: np.ndarray) -> str:
    """The largest of the seeds' largest learned fall probabilities."""
    return "–" if np.isnan(p).all() else f"{np.nanmax(p):.2f}"


def paired(diff: np.ndarray) -> str:
    """The mean of `diff` with its paired t 95 % interval."""
    m = diff.mean()
    half = stats.t.ppf(0.975, diff.size - 1) * diff.std(ddof=1) / np.sqrt(diff.size)
    return f"{m:+.3g} [{m - half:+.3g}, {m + half:+.3g}]"


def main() -> None:
    runs = Path(sys.argv[1])
    configs = sys.argv[2:]
    out = ROOT / "results/design"
    out.mkdir(parents=True, exist_ok=True)
    csv = ["config,objective,seed,method,found,verified,infeasible,designs,cells,qd_score"]
    # The archive's grid as rtw-scan states it in each search's search.md.
    first = next(runs.glob("*/search.md")).read_text()
    slopes, walks = map(int, re.search(r"of its (\d+) × (\d+) cells", first).groups())
    md = [
        "# Design searches against Sobol designs at equal cost\n",
        "`./scripts/design_bench.sh` (`--analyse-only` to tabulate again): each config run with "
        "every seed below by each method, all stopped at the config's budget of simulations. "
        "*found*: the best objective among the designs evaluated within the budget (the search's "
        "own profile); *verified*: the reported best design profiled again on the five times finer "
        "grid and checked by direct simulation. Each difference is the method's minus Sobol's at "
        "the same seed (Sobol's minus the method's for phi_min, the smaller the better), positive "
        "when the method is better, with its paired t 95 % interval over the seeds. *infeasible*: the "
        "share of the designs drawn that fall; *largest p_fall*: the largest learned fall probability of "
        "a design drawn, over every seed (a candidate above the config's `avoid`, ½, is drawn again; "
        "the bad-value variant screens none, so its column is what the screen would have seen). *cells*: the "
        f"archive's cells filled, of {slopes * walks} ({slopes} bins of the widest interval's middle slope × "
        f"{walks} of the share that walks); *QD-score*: the sum of the elites' normalised objectives. Slopes in "
        "rad.\n",
        "| config | method | seeds | found | vs Sobol [95 % CI] | better | verified | vs Sobol "
        "[95 % CI] | better | infeasible | largest p_fall | cells | QD-score | vs Sobol [95 % CI] |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    effects = []
    for c in configs:
        cfg = ROOT / f"configs/design/{c}.toml"
        budget, objective = budget_of(cfg), objective_of(cfg)
        sign = -1.0 if objective == "phi_min" else 1.0
        seeds = sorted(
            int(p.name.rsplit("-", 1)[1]) for p in runs.glob(f"{c}-sobol-*") if p.is_dir()
        )
        res = {}
        for m in METHODS:
            if not all((runs / f"{c}-{m}-{s}").is_dir() for s in seeds):
                continue
            res[m] = [one(runs / f"{c}-{m}-{s}", budget, objective) for s in seeds]
            for s, r in zip(seeds, res[m]):
                csv.append(
                    f"{c},{objective},{s},{m},{r['found']:.6g},{r['verified']:.6g},"
                    f"{r['infeasible']:.4f},{r['designs']},{r['cells']},{r['qd']:.6g}"
                )
        col = lambda m, k: np.array([r[k] for r in res[m]])  # noqa: E731
        for m in res:
            f, v, q = col(m, "found"), col(m, "verified"), col(m, "qd")
            df = sign * (f - col("sobol", "found"))
            dv = sign * (v - col("sobol", "verified"))
            dq = q - col("sobol", "qd")
            vs = m != "sobol"
            md.append(
                f"| {c} | {METHODS[m]} | {len(seeds)} | {f.mean():.4g} | "
                f"{paired(df) if vs else '–'} | {f'{(df > 0).sum()} of {len(seeds)}' if vs else '–'} | "
                f"{v.mean():.4g} | {paired(dv) if vs else '–'} | "
                f"{f'{(dv > 0).sum()} of {len(seeds)}' if vs else '–'} | "
                f"{100 * col(m, 'infeasible').mean():.1f} % | {pmax(col(m, 'p_fall'))} | "
                f"{col(m, 'cells').mean():.1f} | "
                f"{q.mean():.3f} | {paired(dq) if vs else '–'} |"
            )
        # What the learned fall constraint changes: each search with it
        # against the same search without it (avoid = 1), seed by seed.
        for with_, without in (("cmaes", "cmaes-nomodel"), ("archive", "archive-penalty")):
            if with_ in res and without in res:
                same = sum(a["drawn"] == b["drawn"] for a, b in zip(res[with_], res[without], strict=True))
                effects.append(
                    f"| {c} | {METHODS[with_].split(',')[0]} | "
                    f"{paired(100 * (col(with_, 'infeasible') - col(without, 'infeasible')))} | "
                    f"{paired(sign * (col(with_, 'found') - col(without, 'found')))} | "
                    f"{paired(sign * (col(with_, 'verified') - col(without, 'verified')))} | "
                    f"{same} of {len(seeds)} |"
                )
    if effects:
        md += [
            "\n## What the fall model changes\n",
            "Each search with the learned fall constraint minus the same search without it (`avoid = 1`), "
            "seed by seed, with its paired t 95 % interval: the share of the designs drawn that fall (in "
            "percentage points; negative: fewer with the model), the best found and the best verified (positive: better with the model); "
            "*same*: seeds at which the two drew the same designs (ρ, α, f_n, ζ) in the same order.\n",
            "| config | search | infeasible, with − without (pp) | found, with − without | "
            "verified, with − without | same |",
            "|---|---|---:|---:|---:|---:|",
            *effects,
        ]
    (out / "bench.md").write_text("\n".join(md) + "\n")
    (out / "bench-seeds.csv").write_text("\n".join(csv) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
