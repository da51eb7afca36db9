#!/usr/bin/env python3
"""rtw against SciPy on the same model and samples, in one run.

Usage: scripts/scipy_side_by_side.py [N] [--samples FILE.parquet] [--rtw BIN]

Takes the first N (default 12) samples of the paper scan (their inputs from
`results/paper/samples.parquet`), and for each: runs `rtw-scan simulate
--json` (default model, t_max 20 s, no early stop) and the Python/NumPy port
of the same model (scripts/rtwscripts/reference.py) with `scipy.integrate.solve_ivp`
RK45 and terminal events at rtw's default tolerance (rtol 1e-4, atol 1e-6),
from rtw's own initial state (its trace at t = 0: the port does not set the
star down). Prints per sample both labels, both times and RHS counts, then
the ratio of the summed times and the label agreement, with rtw's default
and with rtw's own reference (DOP853 at rtol 1e-13). rtw's time is its
`wall_time_s` (the simulation alone, one thread); the port's is measured
around its run. Samples that cannot stand (a collapse before the push) have
no run to compare and are listed apart.
"""
import argparse
import json
import os
import subprocess
import tempfile
import time

import pandas as pd

from rtwscripts import reference as ref

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RTOL, ATOL = 1e-4, 1e-6
# The strings' natural length over r: rtw's default model's
# (configs/template.toml), given to both sides, so neither runs a hidden
# default of its own.
S = 0.8875


def rtw(binary, p, extra, tol=(RTOL, ATOL)):
    cmd = [binary, "simulate", "--length", str(p.length), "--rho", repr(p.rho), "--alpha",
           repr(p.alpha), "--fn", repr(p.fn), "--zeta", repr(p.zeta), "--phi", repr(p.phi),
           "--set", "stop_when_settled=false", "--set", f"rtol={tol[0]}", "--set", f"atol={tol[1]}",
           "--set", f"strings.rest_length_ratio={S}",
           "--json", *extra]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    return json.loads(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("n", nargs="?", type=int, default=12)
    ap.add_argument("--samples", default=os.path.join(ROOT, "results/paper/samples.parquet"))
    ap.add_argument("--rtw", default=os.path.join(ROOT, "target/release/rtw-scan"))
    a = ap.parse_args()
    rows = pd.read_parquet(a.samples).sort_values("sample_id").head(a.n)
    t_rtw = t_py = 0.0
    agree = agree_ref = rtw_ref = compared = 0
    ratios = []
    print("| sample | rtw | rtw reference | SciPy port | rtw ms | SciPy ms | ratio | rtw RHS | SciPy RHS |")
    print("|---:|---|---|---|---:|---:|---:|---:|---:|")
    apart = []
    with tempfile.TemporaryDirectory() as tmp:
        for p in rows.itertuples():
            out = rtw(a.rtw, p, [])
            # rtw's own reference (the benchmark's): DOP853 at rtol 1e-13.
            reference = rtw(a.rtw, p, ["--set", "method=\"dop853\""], (1e-13, 1e-15))["outcome"]
            trace = os.path.join(tmp, "t.parquet")
            rtw(a.rtw, p, ["--trace", trace, "--set", "trace_dt=100"])
            tr = pd.read_parquet(trace)
            if out["t_end"] == 0.0 or tr.empty:
                apart.append((p.sample_id, out["outcome"], out["failure"]))
                continue
            s0 = tr.iloc[0]
            rods0 = [[s0[f"{k}_{r}"] for k in ("x", "y", "theta", "vx", "vy", "omega")]
                     for r in "abc"]
            codes = [int(s0[f"contact_{r}"]) for r in "abc"]
            model = ref.Model(p.length, p.rho, p.alpha, p.fn, p.zeta, p.phi, S)
            started = time.perf_counter()
            label, detail, stats = ref.simulate(model, rods0, codes, rtol=RTOL, atol=ATOL)
            dt = time.perf_counter() - started
            t_rtw += out["wall_time_s"]
            t_py += dt
            compared += 1
            agree += label == out["outcome"]
            agree_ref += label == reference
            rtw_ref += out["outcome"] == reference
            ratios.append(dt / out["wall_time_s"])
            print(f"| {p.sample_id} | {out['outcome']} | {reference} "
                  f"| {label}{' (' + detail + ')' if detail else ''} "
                  f"| {1e3 * out['wall_time_s']:.2f} | {1e3 * dt:.0f} | {ratios[-1]:.0f}× "
                  f"| {out['rhs_evals']} | {stats['nfev']} |")
    for sid, lab, why in apart:
        print(f"| {sid} | {lab} ({why}) | | not run: no standing start | | | | | |")
    ratios.sort()
    print(f"\n{compared} samples run by both: SciPy {t_py:.2f} s, rtw {t_rtw:.4f} s, "
          f"ratio {t_py / t_rtw:.0f}× (median per sample {ratios[len(ratios) // 2]:.0f}×). "
          f"The port's label agrees with rtw's default on {agree} of {compared}, with rtw's "
          f"reference on {agree_ref}; rtw's default agrees with its reference on {rtw_ref}.")
    print()
    print("| | SciPy port | rtw |")
    print("|---|---:|---:|")
    print(f"| time, {compared} runs | {t_py:.2f} s | {t_rtw:.4f} s |")
    print(f"| ratio (summed times) | {t_py / t_rtw:.0f}× | |")
    print(f"| ratio (median per sample) | {ratios[len(ratios) // 2]:.0f}× | |")
    print(f"| labels that agree with rtw's default | {agree} of {compared} | |")
    print(f"| labels that agree with rtw's reference (DOP853 1e-13) | {agree_ref} of {compared} "
          f"| {rtw_ref} of {compared} |")


if __name__ == "__main__":
    main()
