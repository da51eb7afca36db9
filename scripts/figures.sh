#!/usr/bin/env bash
# Every figure of results/figures/ (Fig. S2, S3, S4, the gait gallery, failure
# rates), from the committed scans results/{paper,fig-s2,fig-s3}/samples.parquet;
# a scan that is missing is first run from configs/<name>.toml. Sets up the
# Python venv (.venv, scripts/requirements.txt) and builds rtw-scan itself.
# Extra arguments go to scripts/figures.py (e.g. --only fig-s3).
set -euo pipefail
cd "$(dirname "$0")/.."

./scripts/venv.sh

cargo build --release -q -p rtw-scan
bin="${CARGO_TARGET_DIR:-target}/release/rtw-scan"

for scan in paper fig-s2 fig-s3; do
  if [ ! -f "results/$scan/samples.parquet" ]; then
    echo "figures: results/$scan/samples.parquet is missing: running configs/$scan.toml" >&2
    "$bin" run "configs/$scan.toml" --out "results/$scan" >/dev/null
  fi
done

exec .venv/bin/python scripts/figures.py --bin "$bin" "$@"
