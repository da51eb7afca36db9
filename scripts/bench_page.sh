#!/usr/bin/env bash
# Today's numbers of docs/performance.md -> results/bench/page.md, whose
# tables scripts/readme_tables.py copies into the page's generated blocks
# (so no number there is typed by hand). About a minute on 2 cores:
#   - Hot path: callgrind instruction counts of one Fig. 7(a) run at the
#     default model (scripts/hot_path.sh; needs valgrind);
#   - Scaling: the paper scan on 1 and 2 threads, alternated, RUNS times
#     each (default 5), medians;
#   - Where the time goes: scripts/time_budget.py over three of those
#     2-thread scans;
#   - SciPy: scripts/scipy_side_by_side.py 16.
# Records the day, the machine and the load average with the numbers. Then
# run `.venv/bin/python scripts/readme_tables.py docs/performance.md docs/performance-scipy.md`.
#
#   ./scripts/bench_page.sh [RUNS]
. "$(dirname "$0")/lib.sh"
runs="${1:-5}"
rtw_venv
rtw_build
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }
{
  echo "# Today's numbers of docs/performance.md: ./scripts/bench_page.sh $runs"
  echo
  echo "Made $(date -u +%F) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)); load average at the start $(load)."
  echo
  echo "## Hot path"
  echo
  ./scripts/hot_path.sh "$tmp/hp"
  echo
  echo "## Scaling"
  echo
  for i in $(seq 1 "$runs"); do
    for t in 1 2; do
      rm -rf "$tmp/scan-$t-$i"
      /usr/bin/time -f "$t %e %U" -a -o "$tmp/times" "$RTW_BIN" run configs/paper.toml \
        --out "$tmp/scan-$t-$i" --threads "$t" --quiet >/dev/null
    done
  done
  .venv/bin/python - "$tmp/times" <<'PY'
import sys
import numpy as np
rows = [line.split() for line in open(sys.argv[1]) if line.strip()]
med = {t: (np.median([float(r[1]) for r in rows if r[0] == t]), np.median([float(r[2]) for r in rows if r[0] == t]))
       for t in ("1", "2")}
print(f"paper scan, {sum(r[0] == '1' for r in rows)} runs per thread count, alternated; medians")
print()
print("| threads | wall s | samples/s | CPU s |")
print("|---:|---:|---:|---:|")
for t, (wall, cpu) in med.items():
    print(f"| {t} | {wall:.2f} | {1000 / wall:.0f} | {cpu:.2f} |")
speedup = med["1"][0] / med["2"][0]
print(f"| 2 against 1 | {speedup:.2f}× | | efficiency {speedup / 2:.2f} |")
PY
  echo
  echo "## Where the time goes"
  echo
  "$RTW_PY" scripts/time_budget.py $(for i in 1 2 3; do echo "$tmp/scan-2-$i/samples.parquet"; done) \
    | sed -n '/^## All/,$p' | tail -n +2
  echo "## SciPy"
  echo
  "$RTW_PY" scripts/scipy_side_by_side.py 16 --rtw "$RTW_BIN"
  echo
  echo "Load average at the end $(load)."
} >"$tmp/page.md"
mkdir -p results/bench
mv "$tmp/page.md" results/bench/page.md
echo "bench_page: results/bench/page.md"
