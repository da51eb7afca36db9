#!/usr/bin/env bash
# The scan report at scale -> results/bench/report-scale.md, whose table
# scripts/readme_tables.py copies into docs/report.md ("Scale"). About five
# minutes on 2 cores:
#   - a 10⁶-row scan: configs/paper.toml with samples = 1000000, run by the
#     test build's fake simulator (--fake-sim 0: labels and outputs from the
#     inputs, no physics; a real 10⁶-row scan takes some 20 minutes, and the
#     report's cost depends on the row count, not on how the rows were made);
#   - the Saltelli study, results/sensitivity/saltelli (229 376 rows);
#   - results/paper (1 000 rows);
# each reported RUNS times (default 3; wall time and peak resident memory by
# /usr/bin/time, medians), with the time of each step of one more run, and
# its page opened RUNS times in headless Chromium (scripts/report_timing.py:
# first view and everything drawn, medians). Records the day, the machine and
# the load average with the numbers.
#
#   ./scripts/report_scale.sh [RUNS]
. "$(dirname "$0")/lib.sh"
runs="${1:-3}"
rtw_install
py=$PWD/$RTW_PY
rtw_build -p rtw-scan -p rtw-scan-test
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
load() { cut -d' ' -f1-3 /proc/loadavg; }
grep -q '^samples = 1000$' configs/paper.toml
sed -e 's/^samples = 1000$/samples = 1000000/' configs/paper.toml >"$tmp/million.toml"
"${RTW_BIN}-test" run "$tmp/million.toml" --out "$tmp/million" --fake-sim 0 --quiet >/dev/null
start_load=$(load)
row() { # NAME DIR ROWS: one table row
  local name=$1 dir=$2 rows=$3 i
  : >"$tmp/times"
  for i in $(seq "$runs"); do
    /usr/bin/time -f "%e %M" -a -o "$tmp/times" "$py" -m rtw report "$dir" --out "$tmp/page.html" --force \
      2>/dev/null >/dev/null
  done
  "$py" scripts/report_steps.py "$dir" "$tmp/steps.html" >"$tmp/steps"
  "$py" scripts/report_timing.py "$tmp/page.html" --runs "$runs" --json "$tmp/timing.json" >/dev/null
  "$py" - "$name" "$rows" "$tmp/times" "$tmp/page.html" "$tmp/timing.json" "$tmp/steps" <<'PY'
import json, statistics, sys
from pathlib import Path
name, rows, times, page, timing, steps = sys.argv[1:]
t = [line.split() for line in open(times) if line.strip()]
wall = statistics.median(float(x[0]) for x in t)
rss = statistics.median(float(x[1]) for x in t) / 1024
m = json.loads(Path(timing).read_text())["median"]
print(f"| {name} | {int(rows):,} | {wall:.1f} | {rss:.0f} | {Path(page).stat().st_size / 1e6:.2f} | "
      f"{m['first-view'] / 1000:.2f} | {m['ready'] / 1000:.1f} | {Path(steps).read_text().strip()} |")
PY
}
{
  echo "# The scan report at scale: ./scripts/report_scale.sh $runs"
  echo
  echo "Made $(date -u +%F) on $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)); load average at the start $start_load."
  echo
  echo "## Scale"
  echo
  echo "| scan | rows | made in (s) | peak memory (MB) | page (MB) | first view (s) | everything drawn (s) | steps of one more run (s) |"
  echo "|---|---:|---:|---:|---:|---:|---:|---|"
  row "paper.toml, 10⁶ samples (fake simulator)" "$tmp/million" 1000000
  row "results/sensitivity/saltelli" results/sensitivity/saltelli 229376
  row "results/paper" results/paper 1000
  echo
  echo "Medians of $runs: the report's wall time and peak resident memory (/usr/bin/time), and the page's first view (header, summary, gait map) and everything drawn in headless Chromium (scripts/report_timing.py). Load average at the end $(load)."
} >"$tmp/report-scale.md"
mkdir -p results/bench
mv "$tmp/report-scale.md" results/bench/report-scale.md
echo "report_scale: results/bench/report-scale.md"
