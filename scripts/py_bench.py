#!/usr/bin/env python3
"""The cost of calling rtw from Python (docs/performance.md, "From Python").

1. ``rtw.simulate`` at Fig. 7(a), many calls: each call's wall time seen from
   Python against the run's own time in Rust (the Outcome's ``wall_time_s``,
   measured inside the same call around the simulation); the overhead is
   median(Python) / median(Rust) − 1.
2. ``rtw.scan("configs/paper.toml")`` against ``rtw-scan run
   configs/paper.toml --out TMP`` (the release binary), alternating, each
   ``--reps`` times; the ratio is median(Python) / median(CLI).

Usage: .venv/bin/python scripts/py_bench.py [--calls 300] [--reps 5]
(after installing the package: .venv/bin/python -m pip install ./crates/rtw-py).
"""

from __future__ import annotations

import argparse
import platform
import shutil
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import rtw

ROOT = Path(__file__).resolve().parents[1]
FIG7A = dict(length=0.8, rho=2.5, alpha=0.125, fn=3.269, zeta=0.0514, phi=0.15)


def simulate_overhead(calls: int) -> tuple[float, float, float]:
    """(median wall time from Python, median run time in Rust, overhead %)."""
    for _ in range(10):  # warm up: page in the module, the allocator, the caches
        rtw.simulate(**FIG7A)
    python, rust = [], []
    for _ in range(calls):
        t = time.perf_counter()
        out = rtw.simulate(**FIG7A)
        python.append(time.perf_counter() - t)
        rust.append(out.wall_time_s)
    mp, mr = statistics.median(python), statistics.median(rust)
    return mp, mr, 100.0 * (mp / mr - 1.0)


def scan_ratio(reps: int, cli: Path) -> tuple[float, float, float]:
    """(median rtw.scan time, median CLI time, ratio) on configs/paper.toml."""
    config = ROOT / "configs" / "paper.toml"
    python, command = [], []
    rows = rtw.scan(config).num_rows  # warm up
    for _ in range(reps):
        out = Path(tempfile.mkdtemp(prefix="py_bench-"))
        try:
            t = time.perf_counter()
            subprocess.run([cli, "run", config, "--out", out, "--quiet"], check=True,
                           stdout=subprocess.DEVNULL)
            command.append(time.perf_counter() - t)
        finally:
            shutil.rmtree(out)
        t = time.perf_counter()
        assert rtw.scan(config).num_rows == rows
        python.append(time.perf_counter() - t)
    mp, mc = statistics.median(python), statistics.median(command)
    return mp, mc, mp / mc


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--calls", type=int, default=300, help="rtw.simulate calls (default 300)")
    ap.add_argument("--reps", type=int, default=5, help="scans of each kind (default 5)")
    a = ap.parse_args()
    if a.calls < 1 or a.reps < 1:
        ap.error("--calls and --reps: must be >= 1")
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "rtw-scan"], cwd=ROOT, check=True)
    cli = ROOT / "target" / "release" / "rtw-scan"
    mp, mr, overhead = simulate_overhead(a.calls)
    print(f"rtw {rtw.__version__}, Python {platform.python_version()}")
    print(f"rtw.simulate at Fig. 7(a), {a.calls} calls: median {mp * 1e3:.3f} ms from Python, "
          f"{mr * 1e3:.3f} ms in Rust: overhead {overhead:.1f} % (target < 5 %)")
    sp, sc, ratio = scan_ratio(a.reps, cli)
    print(f"configs/paper.toml, {a.reps} runs each, alternating: rtw.scan median {sp:.2f} s, "
          f"rtw-scan run median {sc:.2f} s: ratio {ratio:.2f} (target <= 1.1)")


if __name__ == "__main__":
    main()
