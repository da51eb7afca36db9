"""The design search against Sobol designs at equal cost (docs/design.md).

For each config and seed, reads runs/design-bench/CONFIG-METHOD-SEED/
search.parquet (every evaluated design, in order, with the simulations it
cost) and designs.parquet (the reported best, profiled again on the fine
grid), and takes
  - found: the best objective among the designs evaluated before the
    cumulative simulations pass the config's budget (the same count for
    both methods), as the search's own profile gives it;
  - verified: the reported best design's objective on the fine grid;
  - infeasible: the share of evaluated designs with no objective (they fall).
Then the mean over seeds per method, and the mean paired difference
(CMA-ES − Sobol; for phi_min Sobol − CMA-ES, so that positive is better
for the search) with a percentile bootstrap 95 % interval (10 000
resamples of the seeds, seed 0), and a sign count.

Writes results/design/bench.md and results/design/bench-seeds.csv.
Usage: python scripts/design_bench.py RUNS CONFIG [CONFIG ...]
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq

ROOT = Path(__file__).resolve().parent.parent


def budget_of(config: Path) -> int:
    return int(re.search(r"^budget = (\d+)", config.read_text(), re.M).group(1))


def objective_of(config: Path) -> str:
    return re.search(r'^objectives = \["(\w+)"', config.read_text(), re.M).group(1)


def one(run: Path, budget: int, objective: str) -> tuple[float, float, float, int]:
    t = pq.read_table(run / "search.parquet").to_pydict()
    runs = np.cumsum(t["runs"])
    within = runs <= budget
    values = np.array([np.nan if v is None else v for v in t[objective]], dtype=float)
    feasible = np.array(t["feasible"]) & within
    sign = -1.0 if objective == "phi_min" else 1.0
    found = sign * np.nanmax(sign * values[feasible]) if feasible.any() else np.nan
    d = pq.read_table(run / "designs.parquet").to_pydict()
    verified = d[objective][0] if d[objective] else np.nan
    infeasible = 1.0 - np.mean(np.array(t["feasible"])[within])
    return found, verified, infeasible, int(within.sum())


def bootstrap(diff: np.ndarray) -> tuple[float, float]:
    rng = np.random.default_rng(0)
    means = rng.choice(diff, size=(10_000, diff.size), replace=True).mean(axis=1)
    return float(np.percentile(means, 2.5)), float(np.percentile(means, 97.5))


def main() -> None:
    runs = Path(sys.argv[1])
    configs = sys.argv[2:]
    out = ROOT / "results/design"
    out.mkdir(parents=True, exist_ok=True)
    csv = ["config,objective,seed,method,found,verified,infeasible,designs"]
    md = [
        "# Design search against Sobol designs at equal cost\n",
        "`./scripts/design_bench.sh` (`--analyse-only` to tabulate again): each config of "
        "`configs/design/` run with seeds 1–5 by CMA-ES with the learned fall constraint and by a "
        "scrambled Sobol sequence of designs, both stopped at the config's budget of simulations. "
        "*found*: the best objective among the designs evaluated within the budget (the search's "
        "own profile, grid 0.01 or 0.002); *verified*: the reported best design profiled again on the "
        "five times finer grid. Difference: CMA-ES − Sobol (Sobol − CMA-ES for phi_min, the smaller "
        "the better), positive when the search is better; 95 % percentile bootstrap interval over "
        "the seeds. Slopes in rad.\n",
        "| config | objective | budget | CMA-ES found | Sobol found | difference [95 % CI] | CMA-ES better | "
        "CMA-ES verified | Sobol verified | verified difference [95 % CI] | infeasible CMA-ES / Sobol |",
        "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for c in configs:
        cfg = ROOT / f"configs/design/{c}.toml"
        budget, objective = budget_of(cfg), objective_of(cfg)
        sign = -1.0 if objective == "phi_min" else 1.0
        seeds = sorted(
            int(p.name.rsplit("-", 1)[1]) for p in runs.glob(f"{c}-cmaes-*") if p.is_dir()
        )
        res = {}
        for m in ("cmaes", "sobol"):
            res[m] = np.array([one(runs / f"{c}-{m}-{s}", budget, objective) for s in seeds])
            for s, r in zip(seeds, res[m]):
                csv.append(f"{c},{objective},{s},{m},{r[0]:.6g},{r[1]:.6g},{r[2]:.4f},{int(r[3])}")
        a, b = res["cmaes"], res["sobol"]
        d_found = sign * (a[:, 0] - b[:, 0])
        d_ver = sign * (a[:, 1] - b[:, 1])
        lo, hi = bootstrap(d_found)
        vlo, vhi = bootstrap(d_ver)
        md.append(
            f"| {c} | {objective} | {budget} | {a[:, 0].mean():.4g} | {b[:, 0].mean():.4g} | "
            f"{d_found.mean():+.3g} [{lo:+.3g}, {hi:+.3g}] | {int((d_found > 0).sum())} of {len(seeds)} | "
            f"{a[:, 1].mean():.4g} | {b[:, 1].mean():.4g} | {d_ver.mean():+.3g} [{vlo:+.3g}, {vhi:+.3g}] | "
            f"{100 * a[:, 2].mean():.1f} % / {100 * b[:, 2].mean():.1f} % |"
        )
    (out / "bench.md").write_text("\n".join(md) + "\n")
    (out / "bench-seeds.csv").write_text("\n".join(csv) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
