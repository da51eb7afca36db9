#!/usr/bin/env bash
# The design searches against Sobol designs of the same budget
# (docs/design.md): each config of configs/design/ named in CONFIGS, run
# with seeds 1..SEEDS by every method of METHODS, each into
# runs/design-bench/CONFIG-METHOD-SEED; then scripts/design_bench.py
# compares the best objective found within the budget, seed by seed, with
# a paired t interval of the mean difference against Sobol, into
# results/design/bench.md and docs/design.md. The methods:
#   cmaes            CMA-ES with the learned fall constraint
#   cmaes-nomodel    the same without it (avoid = 1): every fall is drawn
#                    and spent, and left out of the update
#   sobol            the designs of a scrambled Sobol sequence (the baseline)
#   archive          MAP-Elites with the learned fall constraint
#   archive-penalty  the same without it (avoid = 1): every fall is drawn,
#                    spent and scored as the users' "bad value" (no cell)
# A run whose folder holds the finished search of the same config is kept,
# so a stopped benchmark goes on where it was.
#   ./scripts/design_bench.sh [--analyse-only]
#   (defaults: SEEDS=10 CONFIGS="widest widest-walk"
#    METHODS="cmaes cmaes-nomodel sobol archive archive-penalty"; about 80 min on two idle cores)
. "$(dirname "$0")/lib.sh"
SEEDS=${SEEDS:-10}
read -r -a CONFIGS <<< "${CONFIGS:-widest widest-walk}"
read -r -a METHODS <<< "${METHODS:-cmaes cmaes-nomodel sobol archive archive-penalty}"
if [[ "${1:-}" != "--analyse-only" ]]; then
  rtw_build
  mkdir -p runs/design-bench
  for c in "${CONFIGS[@]}"; do
    for seed in $(seq 1 "$SEEDS"); do
      for method in "${METHODS[@]}"; do
        cfg=runs/design-bench/$c-$method-$seed.toml
        case $method in
          archive-penalty) keys="method = \"archive\"\navoid = 1.0" ;;
          cmaes-nomodel) keys="method = \"cmaes\"\navoid = 1.0" ;;
          *) keys="method = \"$method\"" ;;
        esac
        out=runs/design-bench/$c-$method-$seed
        sed -e "s/^seed = .*/seed = $seed\n$keys/" -e "s/^name = .*/name = \"$c-$method-$seed\"/" \
          "configs/design/$c.toml" > "$cfg.new"
        # A finished search of the same config is kept: the benchmark goes
        # on where it was stopped (after a build that changes numbers,
        # remove runs/design-bench/ first).
        if cmp -s "$cfg.new" "$cfg" && [[ -f $out/search.md ]]; then
          rm "$cfg.new"
          echo "$c $method seed $seed kept" >&2
          continue
        fi
        mv "$cfg.new" "$cfg"
        "$RTW_BIN" design "$cfg" --out "$out" --quiet --force > /dev/null
        echo "$c $method seed $seed done" >&2
      done
    done
  done
fi
rtw_venv
"$RTW_PY" scripts/design_bench.py runs/design-bench "${CONFIGS[@]}"
