#!/usr/bin/env bash
# Every figure of results/figures/ (Fig. S2, S3, S4, the gait gallery, failure
# rates), from the committed scans results/{paper,fig-s2,fig-s3}/samples.parquet;
# a scan that is missing is first run from configs/<name>.toml. Sets up the
# Python venv (.venv, scripts/requirements.txt) and builds rtw-scan itself.
# Extra arguments go to scripts/figures.py (e.g. --only fig-s3).
. "$(dirname "$0")/lib.sh"

rtw_install

rtw_build

for scan in paper fig-s2 fig-s3; do
  if [ ! -f "results/$scan/samples.parquet" ]; then
    echo "figures: results/$scan/samples.parquet is missing: running configs/$scan.toml" >&2
    "$RTW_BIN" run "configs/$scan.toml" --out "results/$scan" >/dev/null
  fi
done

exec "$RTW_PY" scripts/figures.py --bin "$RTW_BIN" "$@"
