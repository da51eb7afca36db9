#!/usr/bin/env bash
# The design search against the best design of a Sobol scan of the same
# budget (docs/design.md): each config of configs/design/ named below, run
# with seeds 1..SEEDS by CMA-ES (method = "cmaes", the learned fall
# constraint) and by Sobol designs (method = "sobol"), each into
# runs/design-bench/; then scripts/design_bench.py compares the best
# objective found within the budget, per seed, with a bootstrap interval of
# the mean difference, into results/design/bench.md and docs/design.md.
#   ./scripts/design_bench.sh [--analyse-only]
. "$(dirname "$0")/lib.sh"
SEEDS=${SEEDS:-5}
CONFIGS=(widest widest-walk shallowest)
if [[ "${1:-}" != "--analyse-only" ]]; then
  rtw_build
  mkdir -p runs/design-bench
  for c in "${CONFIGS[@]}"; do
    for seed in $(seq 1 "$SEEDS"); do
      for method in cmaes sobol; do
        cfg=runs/design-bench/$c-$method-$seed.toml
        sed -e "s/^seed = .*/seed = $seed\nmethod = \"$method\"/" -e "s/^name = .*/name = \"$c-$method-$seed\"/" \
          "configs/design/$c.toml" > "$cfg"
        "$RTW_BIN" design "$cfg" --out "runs/design-bench/$c-$method-$seed" --quiet --force > /dev/null
        echo "$c $method seed $seed done" >&2
      done
    done
  done
fi
"$RTW_PY" scripts/design_bench.py runs/design-bench "${CONFIGS[@]}"
