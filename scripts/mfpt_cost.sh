#!/usr/bin/env bash
# The cost of the mean first-passage time (docs/robustness-rough.md, "Cost of the
# MFPT"): the paper scan (configs/paper.toml, all 1000 samples; the MFPT is
# computed for its stable gaits) with only `robustness.mfpt=true`, at the
# default roughness (robustness.sigma, 1 cm), on 2 threads, RUNS times
# (default 3). Prints, and writes to results/robustness/mfpt_cost.txt, each
# run's wall time and their median, and how a gait's own time grows with its
# MFPT (the scan's wall_time_s against log10 mfpt, the per-gait median over
# the runs). The scans go to a temporary directory. CONFIG (default
# configs/paper.toml) is for trying the script on a smaller scan, such as
# configs/robustness-map.toml; the result file is then named after it.
# Each run's CPU time (user + sys) is recorded too: on a machine shared with
# other jobs the wall time grows with their load, the CPU time much less, and
# CPU / 2 is what the run would take on 2 idle cores at perfect scaling.
#
#   ./scripts/mfpt_cost.sh [RUNS] [CONFIG]
. "$(dirname "$0")/lib.sh"
runs="${1:-3}"
config="${2:-configs/paper.toml}"
name=$(basename "$config" .toml)
result=results/robustness/mfpt_cost.txt
[[ "$name" == paper ]] || result="results/robustness/mfpt_cost-$name.txt"
rtw_venv
rtw_build
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for i in $(seq 1 "$runs"); do
  /usr/bin/time -f "%e %U %S" -a -o "$tmp/times" \
    "$RTW_BIN" run "$config" --out "$tmp/run$i" --threads 2 --quiet --set robustness.mfpt=true >/dev/null
done
load=$(cut -d' ' -f1-3 /proc/loadavg)
mkdir -p results/robustness
.venv/bin/python - "$tmp" "$runs" "$load" "$config" <<'PY' | tee "$result"
import sys
from pathlib import Path

import numpy as np
import pyarrow.parquet as pq

tmp, runs, load, config = Path(sys.argv[1]), int(sys.argv[2]), sys.argv[3], sys.argv[4]
runs_text = [line.split() for line in (tmp / "times").read_text().splitlines() if line.strip()]
times = [float(r[0]) for r in runs_text]
cpu = [float(r[1]) + float(r[2]) for r in runs_text]
stable = ("skip", "walk", "crawl")
per_run = []
for i in range(1, runs + 1):
    t = pq.read_table(tmp / f"run{i}" / "samples.parquet")
    per_run.append({c: np.array(t.column(c).to_pylist(), dtype=object) for c in ("outcome", "mfpt", "mfpt_hi", "wall_time_s")})
first = per_run[0]
keep = np.isin(first["outcome"], stable)
mfpt = np.array([np.nan if v is None else v for v in first["mfpt"][keep]], dtype=float)
hi = np.array([np.nan if v is None else v for v in first["mfpt_hi"][keep]], dtype=float)
for r in per_run[1:]:
    same = np.array([np.nan if v is None else v for v in r["mfpt"][keep]], dtype=float)
    assert np.array_equal(same, mfpt, equal_nan=True), "the MFPT differs between runs: it must be a pure function of the gait"
wall = np.median(np.array([r["wall_time_s"][keep].astype(float) for r in per_run]), axis=0)
n = int(keep.sum())
print(f"# The cost of the MFPT: ./scripts/mfpt_cost.sh {runs} {config}")
print()
print(f"rtw-scan run {config} --threads 2 --set robustness.mfpt=true (sigma 1 cm, the default), {runs} run(s)")
print("wall times: " + ", ".join(f"{x:.1f} s" for x in times) + f"; median {np.median(times):.1f} s "
      f"({np.median(times) / 60:.2f} min; target 10 min); load average after the runs {load} (2 cores)")
print("CPU times (user + sys): " + ", ".join(f"{x:.1f} s" for x in cpu) + f"; median {np.median(cpu):.1f} s, "
      f"half of it {np.median(cpu) / 2 / 60:.2f} min (2 idle cores at perfect scaling)")
print(f"stable gaits: {n} of {len(first['outcome'])}; per stable gait (wall_time_s, median over the runs): "
      f"median {np.median(wall):.2f} s, mean {wall.mean():.2f} s, 90 % {np.percentile(wall, 90):.2f} s, max {wall.max():.2f} s; "
      f"sum {wall.sum():.0f} s of thread time")
fin = np.isfinite(mfpt)
closed = fin & np.isfinite(hi)
noshow = np.isinf(mfpt)
print(f"MFPT finite {fin.sum()} (interval closed {closed.sum()}, open above {(fin & ~np.isfinite(hi)).sum()}); "
      f"no fall counted (mfpt = inf) {noshow.sum()}; null {(~fin & ~noshow).sum()}")
x, y = np.log10(mfpt[fin]), wall[fin]
slope, icpt = np.polyfit(x, y, 1)
lslope, licpt = np.polyfit(x, np.log10(y), 1)
rho = np.corrcoef(np.argsort(np.argsort(x)), np.argsort(np.argsort(y)))[0, 1]
print(f"time against log10 MFPT over the {fin.sum()} finite MFPTs: {slope:+.3f} s per decade of MFPT "
      f"(intercept {icpt:.2f} s); log-log slope {lslope:+.3f} (time ~ MFPT^{lslope:.2f}); Spearman {rho:+.2f}")
edges = [1, 10, 100, 1e3, 1e4, 1e5, 1e6, np.inf]
print("median time per gait by MFPT: " + "; ".join(
    f"{lo:g}–{hi_:g}: {np.median(wall[fin][(mfpt[fin] >= lo) & (mfpt[fin] < hi_)]):.2f} s ({((mfpt[fin] >= lo) & (mfpt[fin] < hi_)).sum()})"
    for lo, hi_ in zip(edges[:-1], edges[1:]) if ((mfpt[fin] >= lo) & (mfpt[fin] < hi_)).any()
) + (f"; no fall seen: {np.median(wall[noshow]):.2f} s ({noshow.sum()})" if noshow.any() else ""))
PY
