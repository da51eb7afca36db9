#!/usr/bin/env bash
# The refinement benchmark (docs/refine.md): is the label map better for
# samples spent where labels change than for uniform ones, at equal counts?
#
#   results/refine/reference/   a dense uniform scan (configs/refine/reference.toml, 4000 samples)
#   results/refine/seed-S/      for each seed S of 1 … 16: a uniform start of 100 samples (the
#                               same slice, seed S), then
#                               `rtw-scan refine --budget 400 --rounds 16 --seed S`
#   results/refine/summary.md   nearest-neighbour misclassification on the reference, uniform
#                               (64 seeds) vs refined (16 seeds), mean ± SE, and the ratio of
#                               sample counts at equal error with a bootstrap 95 % interval
#                               (scripts/refine_bench.py)
#
#   ./scripts/refine_bench.sh                # ~7 min on two idle cores
#   ROUNDS=4 ./scripts/refine_bench.sh       # the same budget in other rounds
#   REPORT_ONLY=1 ./scripts/refine_bench.sh  # re-tabulate
. "$(dirname "$0")/lib.sh"
OUT=results/refine
SEEDS=$(seq -s " " 1 16)
ROUNDS=${ROUNDS:-16}
if [ -z "${REPORT_ONLY:-}" ]; then
  rtw_build
  rm -rf "$OUT/reference" "$OUT"/seed-*
  "$RTW_BIN" run configs/refine/reference.toml --out "$OUT/reference" --quiet >/dev/null
  mkdir -p runs/refine-bench
  for s in $SEEDS; do
    # The start: the reference's slice and model, 100 samples of seed S.
    sed -e "s/^seed = .*/seed = $s/" -e "s/^samples = .*/samples = 100/" \
        -e "s/^name = .*/name = \"refine-start-$s\"/" configs/refine/reference.toml \
        > "runs/refine-bench/start-$s.toml"
    "$RTW_BIN" run "runs/refine-bench/start-$s.toml" --out "$OUT/seed-$s" --quiet >/dev/null
    "$RTW_BIN" refine "$OUT/seed-$s" --budget 400 --rounds "$ROUNDS" --seed "$s" --quiet
  done
fi
rtw_venv
"$RTW_PY" scripts/refine_bench.py "$OUT" $SEEDS > "$OUT/summary.md"
cat "$OUT/summary.md"
