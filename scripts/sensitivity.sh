#!/usr/bin/env bash
# Sensitivity of the 1000-sample statistic (how far the outcome shares move
# with each modelling or numerical choice): reruns configs/paper.toml
# (the default model) with one choice changed per file of configs/sensitivity/
# -> results/sensitivity/<name>/, and tabulates every run against the default
# run results/paper/ (run the main job first) and against the paper
# -> results/sensitivity/summary.md   (scripts/sensitivity_report.py)
#
#   ./scripts/sensitivity.sh                # all (~10-20 s each on 2 cores; t_max 40 twice that)
#   REPORT_ONLY=1 ./scripts/sensitivity.sh  # re-tabulate
. "$(dirname "$0")/lib.sh"
if [ -z "${REPORT_ONLY:-}" ]; then
  rtw_build
  [ -f results/paper/samples.parquet ] || "$RTW_BIN" run configs/paper.toml --out results/paper >/dev/null
  for f in configs/sensitivity/*.toml; do
    n=$(basename "$f" .toml)
    echo "== $n"
    rm -rf "results/sensitivity/$n"
    "$RTW_BIN" run configs/paper.toml --variant "$f" --out "results/sensitivity/$n" >/dev/null
  done
fi
rtw_install
"$RTW_PY" scripts/sensitivity_report.py results/paper results/sensitivity
