#!/usr/bin/env python3
"""Where a scan's time goes, measured in time rather than instructions.

Fits each sample's own `wall_time_s` to the work it did,

    wall_time_s ≈ a · rhs_evals + c · events + d,

by least squares over the samples of one or more scan files, and prints the
cost of one RHS evaluation with its share of the step around it (stage
arithmetic, the guards at the step's end and their rates, the crossing test,
the observer: steps are not a term of their own, a step is 6.2–7.6 RHS
evaluations in every sample, too collinear to separate), one event (root
finding, reset, restart, the discarded rest of the step) and one sample
(set-up, initial state, labels), with each term's share of the summed sample
time. The samples differ enough in their events per RHS evaluation for the
terms to separate (R² is printed). Compare the first row with criterion's
`rhs` (`cargo bench -p rtw-model --features internals --bench model -- rhs`), the RHS alone.

Usage: scripts/time_budget.py SAMPLES.parquet [SAMPLES.parquet ...]
(docs/performance.md, "Where the time goes").
"""

import sys

import numpy as np
import pyarrow.parquet as pq

TERMS = [
    ("RHS evaluation, with its step", "rhs_evals", 1e9, "ns"),
    ("event", "events", 1e6, "µs"),
    ("sample", None, 1e6, "µs"),
]


def fit(path):
    t = pq.read_table(path, columns=["rhs_evals", "events", "wall_time_s"])
    cols = {n: t.column(n).to_numpy().astype(float) for n in t.column_names}
    wall = cols["wall_time_s"]
    x = np.column_stack(
        [cols[c] if c else np.ones_like(wall) for _, c, _, _ in TERMS]
    )
    coef, *_ = np.linalg.lstsq(x, wall, rcond=None)
    resid = wall - x @ coef
    r2 = 1.0 - (resid @ resid) / ((wall - wall.mean()) @ (wall - wall.mean()))
    share = coef * x.sum(axis=0) / wall.sum()
    return coef, share, r2, wall.sum(), len(wall)


def main(paths):
    if not paths:
        sys.exit(__doc__)
    fits = [fit(path) for path in paths]
    for path, (coef, share, r2, total, n) in zip(paths, fits):
        print(f"{path}: {n} samples, summed sample time {total:.3f} s, R² {r2:.3f}")
        print("| per | cost | share of the time |")
        print("|---|---:|---:|")
        for (name, _, scale, unit), c, s in zip(TERMS, coef, share):
            print(f"| {name} | {c * scale:.1f} {unit} | {100 * s:.0f} % |")
        print()
    if len(fits) > 1:
        def span(values, fmt):
            lo, hi = fmt.format(min(values)), fmt.format(max(values))
            return lo if lo == hi else f"{lo}–{hi}"

        print(f"## All {len(fits)} scans")
        print()
        print(f"| per | cost ({len(fits)} scans) | share of the summed sample time |")
        print("|---|---:|---:|")
        for i, (name, _, scale, unit) in enumerate(TERMS):
            print(f"| {name} | {span([f[0][i] * scale for f in fits], '{:.1f}')} {unit} "
                  f"| {span([100 * f[1][i] for f in fits], '{:.0f}')} % |")
        print(f"| R² of the fit | {span([f[2] for f in fits], '{:.3f}')} | |")
        print(f"| summed sample time | {span([f[3] for f in fits], '{:.2f}')} s | |")
        print()


if __name__ == "__main__":
    main(sys.argv[1:])
