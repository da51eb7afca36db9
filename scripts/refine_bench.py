"""The refinement benchmark's report (scripts/refine_bench.sh, docs/refine.md).

    refine_bench.py RESULTS SEED...   -> Markdown on stdout

The error of a set of samples is the nearest-neighbour misclassification of
its label map on the dense reference scan RESULTS/reference: the share of the
reference's samples whose outcome differs from that of the nearest sample of
the set (Euclidean, each uniform axis scaled to [0, 1]). Uniform arm: for each
of UNIFORM_SEEDS seeds (independent of the refined arm's), n samples drawn
without replacement from the reference itself (a uniform sample), scored on
the reference's other samples. Refined arm: for
each seed, the first n rows of RESULTS/seed-S/refine/samples.parquet (the
uniform start, then the rounds in order), scored on every reference sample.
The ratio of sample counts at equal error compares the refined count with the
uniform count of the same mean error (linear interpolation of log error in
log n between the uniform counts measured). Its 95 % interval is a
percentile bootstrap over seeds: both arms' seeds resampled with replacement,
the ratio recomputed from the resampled means, BOOTSTRAP times.
"""

import json
import sys
import tomllib
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq
from scipy.spatial import cKDTree

UNIFORM_COUNTS = [100, 150, 200, 300, 400, 500, 700, 1000, 1400, 2000, 2800]
# The uniform arm costs no simulation (it draws from the reference), so it
# gets many seeds: its curve's noise then adds little to the ratio's.
UNIFORM_SEEDS = 64
BOOTSTRAP = 2000
GOAL = 1 / 3


def read(path):
    """The unit-box points (the scan's uniform axes) and outcome labels of a scan file."""
    f = pq.ParquetFile(path)
    meta = {k.decode(): v.decode() for k, v in f.metadata.metadata.items()}
    cfg = tomllib.loads(meta["rtw.config"])
    axes = [(k, v["uniform"]) for k, v in cfg["params"].items() if isinstance(v, dict) and "uniform" in v]
    t = f.read()
    x = np.column_stack([(t.column(k).to_numpy() - lo) / (hi - lo) for k, (lo, hi) in axes])
    y = np.array(t.column("outcome").cast("string").to_pylist())
    return x, y, [k for k, _ in axes], meta


def error(train_x, train_y, test_x, test_y):
    _, j = cKDTree(train_x).query(test_x, k=1)
    return float(np.mean(train_y[j] != test_y))


def mean_se(values):
    v = np.asarray(values, dtype=float)
    return v.mean(), (v.std(ddof=1) / np.sqrt(len(v)) if len(v) > 1 else float("nan"))


def equal_error_count(target, counts, errors):
    """The uniform count whose (interpolated) mean error is `target`, or None beyond the range."""
    le, ln = np.log(errors), np.log(counts)
    for a in range(len(counts) - 1):
        lo, hi = le[a], le[a + 1]
        if min(lo, hi) <= np.log(target) <= max(lo, hi) and lo != hi:
            w = (np.log(target) - lo) / (hi - lo)
            return float(np.exp(ln[a] + w * (ln[a + 1] - ln[a])))
    return None


def main():
    root = Path(sys.argv[1])
    seeds = [int(s) for s in sys.argv[2:]]
    rx, ry, names, _ = read(root / "reference" / "samples.parquet")
    uniform = {n: [] for n in UNIFORM_COUNTS}
    for s in range(1, UNIFORM_SEEDS + 1):
        rng = np.random.default_rng([s, 0x0F0])
        order = rng.permutation(len(rx))
        for n in UNIFORM_COUNTS:
            tr, te = order[:n], order[n:]
            uniform[n].append(error(rx[tr], ry[tr], rx[te], ry[te]))
    refined, about = {}, None
    for s in seeds:
        x, y, _, meta = read(root / f"seed-{s}" / "refine" / "samples.parquet")
        about = json.loads(meta["rtw.refine"])
        start = len(x) - about["budget"]
        step = about["budget"] // about["rounds"]
        for n in range(start, len(x) + 1, step):
            refined.setdefault(n, []).append(error(x[:n], y[:n], rx, ry))
    u_mean = [mean_se(uniform[n])[0] for n in UNIFORM_COUNTS]
    labels, counts = np.unique(ry, return_counts=True)
    out = [
        "# Refinement benchmark: samples spent where labels change",
        "",
        f"Reference: `{root / 'reference'}`, {len(rx)} uniform samples of ({', '.join(names)}) "
        f"({', '.join(f'{l} {c}' for l, c in zip(labels, counts))}). "
        f"Seeds {', '.join(map(str, seeds))}; refined: a uniform start of {start} samples, then "
        f"`rtw-scan refine --budget {about['budget']} --rounds {about['rounds']}`.",
        "",
        "Error: nearest-neighbour misclassification of the label map on the reference "
        "(mean ± standard error over the seeds). At the start's count both arms are uniform "
        "samples (of different seeds): their difference there is sampling noise.",
        "",
        "| samples | uniform error | refined error | uniform samples at the refined error | ratio |",
        "|---:|---:|---:|---:|---:|",
    ]
    ratios = {}
    for n in sorted(set(UNIFORM_COUNTS) | set(refined)):
        u = "{:.4f} ± {:.4f}".format(*mean_se(uniform[n])) if n in uniform else "–"
        if n in refined:
            m, se = mean_se(refined[n])
            eq = equal_error_count(m, UNIFORM_COUNTS, u_mean)
            ratios[n] = (n / eq) if eq else None
            r = f"{m:.4f} ± {se:.4f}"
            e = f"{eq:.0f}" if eq else f"> {UNIFORM_COUNTS[-1]}" if m < u_mean[-1] else "–"
            q = f"{n / eq:.2f}" if eq else f"< {n / UNIFORM_COUNTS[-1]:.2f}" if m < u_mean[-1] else "–"
        else:
            r = e = q = "–"
        out.append(f"| {n} | {u} | {r} | {e} | {q} |")
    out += ["", "## The ratio with its interval", ""]
    out += [
        f"Refined count / uniform count of the same mean error, with a percentile bootstrap 95 % "
        f"interval over the seeds ({BOOTSTRAP} resamples of the {len(seeds)} refined and "
        f"{UNIFORM_SEEDS} uniform seeds); the goal is at most 1/3.",
        "",
        "| refined samples | ratio | 95 % interval | 1/3 is |",
        "|---:|---:|---:|---|",
    ]
    boot = np.random.default_rng(12345)
    u_arr = {n: np.asarray(uniform[n]) for n in UNIFORM_COUNTS}
    for n in sorted(refined):
        if n <= start or ratios.get(n) is None:
            continue
        r_arr = np.asarray(refined[n])
        draws = []
        for _ in range(BOOTSTRAP):
            um = [u_arr[c][boot.integers(0, len(u_arr[c]), len(u_arr[c]))].mean() for c in UNIFORM_COUNTS]
            rm = r_arr[boot.integers(0, len(r_arr), len(r_arr))].mean()
            eq = equal_error_count(rm, UNIFORM_COUNTS, um)
            draws.append(n / eq if eq else np.nan)
        lo, hi = np.nanpercentile(draws, [2.5, 97.5])
        where = (
            "above it: the goal is met"
            if GOAL > hi
            else "below it: the goal is missed"
            if GOAL < lo
            else "inside it: the benchmark cannot tell"
        )
        out.append(f"| {n} | {ratios[n]:.2f} | [{lo:.2f}, {hi:.2f}] | {where} |")
    _, j = cKDTree(rx).query(rx, k=2)
    loo = float(np.mean(ry[j[:, 1]] != ry))
    out += [
        "",
        "## The floor",
        "",
        "| reference samples | leave-one-out nearest-neighbour error |",
        "|---:|---:|",
        f"| {len(rx)} | {loo:.4f} |",
        "",
    ]
    print("\n".join(out))


if __name__ == "__main__":
    main()
