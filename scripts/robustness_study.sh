#!/usr/bin/env bash
# The robustness study of docs/robustness-study.md -> results/robustness/, every
# measure on one population:
#   1. the (φ, f_n) map around Fig. 7(a), configs/robustness-map.toml (9 × 9),
#   2. the paper scan (configs/paper.toml, all 1000 samples; the measures are
#      taken for its stable gaits),
#   both with Floquet max |μ| (limit_cycle), step_down_max, step_down_h50,
#   the gait sensitivity norm, the Monte Carlo steps to fall and the mean
#   first-passage time (mfpt, mfpt_lo, mfpt_hi, fall_rate), every
#   robustness key at its default (σ = robustness.sigma, 1 cm; 0.8 m patches);
#   3. both again with the rough slope drawn from terrain seeds 100 and 200
#      (only the drawn columns: steps_to_fall and mfpt; seed100/, seed200/),
#      so that every statistic of the MFPT comes with its spread over draws
#      (trial i of steps_to_fall walks seed terrain.seed + i, so the three
#      draws share no trial up to 100 trials);
#   3b. the paper scan again with the MFPT alone at σ = 5 and 3 cm
#      (roughness/paper-0.05/, roughness/paper-0.03/), and at 5 cm on the
#      slope of terrain.seed 100 (roughness/paper-0.05-seed100/): whether
#      the ranking on rough ground carries to the default 1 cm
#      (roughness.md);
#   4. scripts/step_down_curve.py: the survival curves of the Fig. 7(a)
#      walk and of a walk, a skip and a crawl of the paper scan
#      (step_down_curve.md);
#   5. scripts/robustness_study.py: the rank correlations on the gaits where
#      every measure is defined, the undefined counts, the censored model of
#      log MFPT, the ten longest-walking designs, map-mfpt.png, map.png,
#      paper.png and summary.md.
# `--analyse-only` runs step 5 on the scans already in results/robustness/.
# Sets up the Python venv (.venv, the package rtw) and builds rtw-scan.
. "$(dirname "$0")/lib.sh"

rtw_install
out=results/robustness
mkdir -p "$out"
if [[ "${1:-}" != "--analyse-only" ]]; then
  rtw_build
  seeds=(100 200)
  rm -rf "$out/map" "$out/paper" "$out"/seed* "$out/roughness"
  measures=(--set limit_cycle=true --set robustness.step_down=true
    --set robustness.step_down_h50=true --set robustness.gsn=true
    --set robustness.steps_to_fall=true --set robustness.mfpt=true)
  t0=$(date +%s.%N)
  "$RTW_BIN" run configs/robustness-map.toml --out "$out/map" --quiet "${measures[@]}" >/dev/null
  t1=$(date +%s.%N)
  "$RTW_BIN" run configs/paper.toml --out "$out/paper" --quiet "${measures[@]}" >/dev/null
  t2=$(date +%s.%N)
  for s in "${seeds[@]}"; do
    for c in map paper; do
      config=configs/paper.toml
      [[ $c == map ]] && config=configs/robustness-map.toml
      "$RTW_BIN" run "$config" --out "$out/seed$s/$c" --quiet --set terrain.seed="$s" \
        --set robustness.steps_to_fall=true --set robustness.mfpt=true >/dev/null
    done
  done
  for sigma in 0.05 0.03; do
    "$RTW_BIN" run configs/paper.toml --out "$out/roughness/paper-$sigma" --quiet \
      --set robustness.mfpt=true --set robustness.sigma="$sigma" >/dev/null
  done
  "$RTW_BIN" run configs/paper.toml --out "$out/roughness/paper-0.05-seed100" --quiet \
    --set robustness.mfpt=true --set robustness.sigma=0.05 --set terrain.seed=100 >/dev/null
  t3=$(date +%s.%N)
  # The survival curves of four gaits at stated heights (a few seconds).
  "$RTW_PY" scripts/step_down_curve.py "$out/step_down_curve.md" >/dev/null
  threads=$(nproc)
  python3 -c "print(f'map_scan_(all_measures)={$t1 - $t0:.1f} s;paper_scan_(all_measures)={$t2 - $t1:.1f} s;'
    f'both_scans_at_${#seeds[@]}_more_terrain_seeds_(steps_to_fall_and_mfpt)_and_the_paper_scan_at_5_and_3_cm_and_5_cm_on_seed_100_(mfpt)={$t3 - $t2:.1f} s;threads=$threads')" \
    >"$out/times.txt"
fi
"$RTW_PY" scripts/robustness_stats.py >/dev/null # its self-check against SciPy and a simulated sample
"$RTW_PY" scripts/robustness_study.py "$out" --times "$(cat "$out/times.txt")" >/dev/null
echo "robustness_study: done ($out/summary.md)"
