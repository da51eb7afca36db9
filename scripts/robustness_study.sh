#!/usr/bin/env bash
# The robustness study of docs/robustness.md -> results/robustness/:
#   1. the (φ, f_n) map around Fig. 7(a), configs/robustness-map.toml (9 × 9),
#      with Floquet max |μ|, step_down_max and the Monte Carlo steps to fall;
#   2. the paper scan (configs/paper.toml, all 1000 samples; the measures are
#      taken for its stable gaits) with the same measures;
#   (both with the gait sensitivity norm too when rtw has robustness.gsn);
#   3. the cost of the steps to fall per design point: the map with and
#      without robustness.steps_to_fall, one thread each;
#   4. scripts/robustness_study.py: the Spearman correlations with bootstrap
#      intervals, the most robust designs, map.png and paper.png, summary.md.
# Sets up the Python venv (.venv) and builds rtw-scan.
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/venv.sh
cargo build --release -q -p rtw-scan
bin="${CARGO_TARGET_DIR:-target}/release/rtw-scan"
out=results/robustness
mkdir -p "$out"
rm -rf "$out/map" "$out/paper"

fig7a=(--length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15)
gsn=()
if "$bin" simulate "${fig7a[@]}" --set robustness.gsn=true --json >/dev/null 2>&1; then
  gsn=(--set robustness.gsn=true)
fi

t0=$(date +%s.%N)
"$bin" run configs/robustness-map.toml --out "$out/map" --quiet "${gsn[@]}" >/dev/null
t1=$(date +%s.%N)
"$bin" run configs/paper.toml --out "$out/paper" --quiet --set limit_cycle=true \
  --set robustness.step_down=true --set robustness.steps_to_fall=true "${gsn[@]}" >/dev/null
t2=$(date +%s.%N)

# The cost per design point, one thread each, in scratch directories.
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
s0=$(date +%s.%N)
"$bin" run configs/robustness-map.toml --out "$tmp/plain" --quiet --threads 1 \
  --set robustness.step_down=false --set robustness.steps_to_fall=false >/dev/null
s1=$(date +%s.%N)
"$bin" run configs/robustness-map.toml --out "$tmp/mc" --quiet --threads 1 \
  --set robustness.step_down=false >/dev/null
s2=$(date +%s.%N)
stable=$(.venv/bin/python -c "
import pyarrow.parquet as pq
print(sum(o in ('skip', 'walk', 'crawl') for o in pq.read_table('$out/map/samples.parquet').column('outcome').to_pylist()))")
cost=$(python3 -c "print(f'{($s2 - $s1 - ($s1 - $s0)) / $stable * 1e3:.0f} ms per stable gait ({$s1 - $s0:.1f} s plain, {$s2 - $s1:.1f} s with steps_to_fall, {$stable} stable gaits of 81, one thread)')")

times="map_scan_(all_measures)=$(python3 -c "print(f'{$t1 - $t0:.1f} s')");paper_scan_(all_measures)=$(python3 -c "print(f'{$t2 - $t1:.1f} s')");steps_to_fall_cost=$cost;study_total=$(python3 -c "print(f'{$s2 - $t0:.1f} s (without the venv and the build)')")"
.venv/bin/python scripts/robustness_study.py "$out" --times "$times" >/dev/null
echo "robustness_study: done ($out/summary.md)"
