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
  ./scripts/venv.sh
  out=$(mktemp -d)
  cargo run --release -q -p rtw-scan -- run configs/smoke.toml --out "$out" >/dev/null
  .venv/bin/python scripts/check_parquet.py "$out/samples.parquet"
  rm -rf "$out"
fi
echo "== generated tables match the committed results they are made from"
# The variant study's and the reproduction's tables, and their copies in
# README.md and docs/*.md, are regenerated from the committed results and must
# not change: no number in them is typed by hand.
check=$(mktemp -d)
docs=(README.md docs/*.md)
mkdir -p "$check/docs"
for f in "${docs[@]}"; do cp "$f" "$check/$f"; done
.venv/bin/python scripts/variants_report.py results/variants >/dev/null
.venv/bin/python scripts/reproduction_report.py >/dev/null
.venv/bin/python scripts/readme_tables.py "${docs[@]/#/$check/}" >/dev/null
for f in "${docs[@]}"; do diff -u "$f" "$check/$f"; done
git diff --exit-code -- results/variants/summary.md results/variants/summary.json results/reproduction.md
rm -rf "$check"

echo "== slurm: a 4-task job array + merge on a one-node cluster (scripts/test_slurm.sh)"
./scripts/test_slurm.sh

echo "all checks passed"
