#!/usr/bin/env bash
# The MFPT by adaptive multilevel splitting with a learned score
# (crates/rtw-model/src/run/mfpt_splitting.rs) at Fig. 7(a), against the
# counting references where those exist (results/robustness/mfpt_depth_*.md
# and the counted `rtw-scan simulate ... --set robustness.mfpt=true`):
# σ = 3 and 2 cm, then 1.5 and 1 cm with the interval and the time.
# Each run learns its score at 5 cm (400 walks) and splits REPLICAS
# excursions in BATCHES batches; at 3 cm it also measures the score's AUC
# on 40 plain walks at the target roughness. One run at a time, one core
# each. Writes results/robustness/mfpt_splitting.md.
#
#   ./scripts/mfpt_split_check.sh [REPLICAS [BATCHES [SIGMAS...]]]
set -euo pipefail
cd "$(dirname "$0")/.."
replicas="${1:-400}"
batches="${2:-8}"
shift 2 || true
sigmas=("$@")
[[ ${#sigmas[@]} -gt 0 ]] || sigmas=(0.03 0.02 0.015 0.01)
for v in "$replicas" "$batches"; do
  if ! [[ $v =~ ^[1-9][0-9]*$ ]] || [[ $v -lt 2 ]]; then
    echo "mfpt_split_check: REPLICAS and BATCHES must be whole numbers, at least 2 (got $v)" >&2
    exit 2
  fi
done
out="results/robustness/mfpt_splitting.md"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
# The test binary, copied: every roughness runs the same build.
built=$(nice -n 15 cargo test --release -p rtw-model --lib --no-run 2>&1 |
  sed -n 's/.*Executable unittests src\/lib.rs (\(.*\))/\1/p')
cp "$built" "$tmp/rtw-model-tests"
declare -A ref=(
  [0.05]="≈ 150 (counted)"
  [0.03]="8 056 [6 839, 9 558] (counted)"
  [0.02]="822 857 [591 661, 1 181 355] (counted, mfpt_depth_0.02.md)"
)
for s in "${sigmas[@]}"; do
  target=0
  [[ $s == 0.03 ]] && target=40
  echo "sigma $s ..." >&2
  TIMEFORMAT=%U
  { time RTW_SPLIT_SIGMA="$s" RTW_SPLIT_REPLICAS="$replicas" RTW_SPLIT_BATCHES="$batches" \
      RTW_SPLIT_TARGET_WALKS="$target" RTW_SPLIT_MAX_STEPS=40000 \
      nice -n 15 "$tmp/rtw-model-tests" mfpt_split_fig7a --ignored --nocapture \
      >/dev/null 2>"$tmp/$s.txt"; } 2>"$tmp/$s.cpu"
done
# A quantity a run printed (empty when it did not).
value() { { grep -E "^$2=" "$tmp/$1.txt" || true; } | head -1 | cut -d= -f2-; }
{
  echo "# The MFPT by splitting with a learned score: ./scripts/mfpt_split_check.sh $replicas $batches ${sigmas[*]}"
  echo
  echo "Fig. 7(a) (\`Params::fig7a()\`, default options, 0.8 m patches, terrain.seed 0) on the rough slope of σ."
  echo "The score: a logistic regression of P(fall within 3 steps | extended state) learned on 400 plain walks at 5 cm"
  echo "(AUC on the held-out quarter below), averaged over the steps (weight 0.3 a step); the splitting: $batches batches of $replicas excursions from the better half"
  echo "(by score) of a 32-walker Fleming–Viot cloud, one killed per iteration. MFPT by renewal,"
  echo "E[T | returned] (1 − p)/p + E[T | fell], from the start (the cloud's burn-in added). CPU time: user seconds of the one-thread run."
  echo
  echo "| σ (m) | splitting MFPT [95 %] | counting reference | p [95 %] | E[T\\|ret.] | E[T\\|fell] | steps | CPU s | train AUC | AUC at σ |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  for s in "${sigmas[@]}"; do
    auc=$(value "$s" target_auc)
    [[ -n $auc ]] && auc="$auc ($(value "$s" target_falls) falls in $(value "$s" target_steps) steps)"
    echo "| $s | $(value "$s" mfpt) [$(value "$s" mfpt_lo), $(value "$s" mfpt_hi)] | ${ref[$s]:-none (beyond counting)} | $(value "$s" p) [$(value "$s" p_lo), $(value "$s" p_hi)] | $(value "$s" returned_steps) | $(value "$s" fall_steps) | $(value "$s" steps) | $(cat "$tmp/$s.cpu") | $(value "$s" train_auc) | ${auc:-—} |"
  done
  echo
  echo "## Each batch"
  echo
  echo "| σ (m) | p̂ per batch | distinct ancestors of the final excursions | iterations | fell of $replicas |"
  echo "|---|---|---|---|---|"
  for s in "${sigmas[@]}"; do
    echo "| $s | $(value "$s" batch_p) | $(value "$s" batch_ancestors) | $(value "$s" batch_iterations) | $(value "$s" batch_fell) |"
  done
  echo
  echo "## How each batch's genealogy narrowed"
  echo
  echo "Per batch: the distinct first-iteration ancestors of the $replicas excursions after a quarter, half, three quarters and all of its"
  echo "iterations; and the levels there (the score, the learned log-odds averaged over the steps), A's level first."
  echo
  echo "| σ (m) | ancestors | levels |"
  echo "|---|---|---|"
  for s in "${sigmas[@]}"; do
    echo "| $s | $(value "$s" batch_ancestors_path) | $(value "$s" batch_levels_path) |"
  done
  echo
  echo "At 3 cm, the unsmoothed score's mean quantile among the plain walks' states at 1, 2, 3, 5, 10, 20, 40 and 80 steps"
  echo "before a fall: $(value 0.03 target_lags)."
  echo
} >"$out"
cat "$out"
