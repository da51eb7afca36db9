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
echo "== fault injection: kills, a full disk, corrupt pages (scripts/fault_inject.sh)"
./scripts/fault_inject.sh

echo "== generated tables match the committed results they are made from"
# The variant study's and the reproduction's tables, and the README's copies
# of them, are regenerated from the committed results and must not change:
# no number in them is typed by hand.
check=$(mktemp -d)
cp README.md "$check/README.md"
.venv/bin/python scripts/variants_report.py results/variants >/dev/null
.venv/bin/python scripts/reproduction_report.py >/dev/null
.venv/bin/python scripts/readme_tables.py "$check/README.md" >/dev/null
diff -u README.md "$check/README.md"
git diff --exit-code -- results/variants/summary.md results/variants/summary.json results/reproduction.md
rm -rf "$check"

echo "== slurm: a 4-task job array + merge on a one-node cluster (scripts/test_slurm.sh)"
./scripts/test_slurm.sh

echo "all checks passed"
