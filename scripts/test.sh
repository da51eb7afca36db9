#!/usr/bin/env bash
# The project's test command (README): formatting, lints, every Rust test,
# the Python interoperability check of the Parquet output, and the Slurm test
# (a real one-node cluster running a sharded scan).
# Sets up what it needs on a fresh machine (a Python venv under .venv; Slurm
# and munge from Debian's packages, which needs root).
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy"
cargo clippy --workspace --all-targets --release -- -D warnings

echo "== cargo test"
cargo test --workspace --release

if [ -f scripts/check_parquet.py ]; then
  echo "== python interop (pandas, polars, pyarrow)"
  if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
  fi
  .venv/bin/pip install --quiet --disable-pip-version-check -r scripts/requirements.txt
  out=$(mktemp -d)
  cargo run --release -q -p rtw-scan -- run configs/smoke.toml --out "$out" >/dev/null
  .venv/bin/python scripts/check_parquet.py "$out/samples.parquet"
  rm -rf "$out"
fi
echo "== slurm: a 4-task job array + merge on a one-node cluster (scripts/test_slurm.sh)"
./scripts/test_slurm.sh

echo "all checks passed"
