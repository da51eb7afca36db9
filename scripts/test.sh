#!/usr/bin/env bash
# The project's test command (README, docs/testing.md), in three tiers:
#   1. Rust (any user, only the toolchain): fmt, clippy, rustdoc, every Rust test;
#   2. Python (python3 with venv; pip fetches scripts/requirements.txt into
#      .venv the first time): the pandas/polars/pyarrow check of the Parquet
#      output, that every committed result called the default model's is at
#      the default model, the Python package (built and installed into .venv, its pytest
#      tests), that Cargo.toml's rust-version covers every dependency's, and
#      that the generated tables in README.md and docs/*.md match the
#      committed results;
#   3. Slurm: a sharded scan on a real one-node cluster (scripts/test_slurm.sh;
#      installs Slurm and munge from Debian's packages and starts their
#      daemons, so it needs root). As root (CI: .ci/run) it always runs; as
#      another user it is skipped, saying so and how to run it, and the
#      command passes on the other two tiers.
set -euo pipefail
cd "$(dirname "$0")/.."

echo "== the Rust toolchain is new enough (scripts/check_toolchain.sh)"
./scripts/check_toolchain.sh

echo "== cargo fmt --check"
cargo fmt --all -- --check

echo "== cargo clippy"
cargo clippy --workspace --all-targets --release -- -D warnings

echo "== cargo doc: every intra-doc link resolves and public docs link only public items"
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --release --quiet

echo "== cargo test"
cargo test --workspace --release

if [ -f scripts/check_parquet.py ]; then
  echo "== python interop (pandas, polars, pyarrow)"
  ./scripts/venv.sh
  out=$(mktemp -d)
  cargo run --release -q -p rtw-scan -- run configs/smoke.toml --out "$out" >/dev/null
  .venv/bin/python scripts/check_parquet.py "$out/samples.parquet"
  echo "== every committed result called the default model's is at the default model (scripts/check_default_model.py)"
  # The smoke config sets no model key: its scan's rtw.variant is the library's default.
  .venv/bin/python scripts/check_default_model.py "$out/samples.parquet"
  rm -rf "$out"
fi
echo "== the Python package rtw (crates/rtw-py): installed into .venv, then pytest"
./scripts/venv.sh
# maturin comes from scripts/requirements.txt (found on PATH in .venv/bin) and
# builds in the workspace's target/, so an unchanged crate is only relinked.
PATH="$PWD/.venv/bin:$PATH" .venv/bin/python -m pip install --quiet --disable-pip-version-check \
  --no-build-isolation ./crates/rtw-py
# The scan report's browser test (crates/rtw-py/tests/test_report_browser.py) drives
# Debian's headless Chromium through its chromedriver: installed here as root when
# missing; as another user without them that test is skipped, saying so.
if ! command -v chromium >/dev/null || ! command -v chromedriver >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then
    echo "== installing chromium and chromium-driver (Debian) for the report's browser test"
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium chromium-driver >/dev/null
  else
    echo "== report browser test: SKIPPED unless chromium and chromium-driver are installed (not root:"
    echo "   run sudo apt-get install -y chromium chromium-driver, or this script as root)"
  fi
fi
.venv/bin/python -m pytest -q -rs crates/rtw-py/tests
echo "   (the report's browser test keeps its screenshot in ${CARGO_TARGET_DIR:-target}/report-test/screenshot.png)"
echo "== README.md's Python example, in a venv made by its install line (scripts/check_readme_python.sh)"
./scripts/check_readme_python.sh
echo "== the quickstart notebook, executed (scripts/run_notebook.sh)"
./scripts/run_notebook.sh
echo "== every command README.md and docs/*.md document, run as written in a temporary folder (scripts/check_doc_commands.py)"
.venv/bin/python scripts/check_doc_commands.py
echo "== the documentation site: built with every warning an error, every local link and anchor checked, its first page rendered in headless Chromium (scripts/docs_site.sh)"
./scripts/docs_site.sh
echo "== every Markdown table row in README.md, docs/ and results/ has its header's cells (scripts/check_markdown_tables.py)"
.venv/bin/python scripts/check_markdown_tables.py
echo "== every number the docs' prose quotes from a results file is the file's (scripts/check_doc_numbers.py)"
.venv/bin/python scripts/check_doc_numbers.py
echo "== no file over 600 lines outside its tests, no import cycle (scripts/check_structure.py)"
.venv/bin/python scripts/check_structure.py
echo "== the maps of the subcommands (README, docs/commands.md, docs/cli.md, docs/architecture.md, rtw-scan's lib.rs) name every one (scripts/check_maps.py)"
.venv/bin/python scripts/check_maps.py
echo "== rust-version covers every dependency (scripts/check_msrv.py)"
.venv/bin/python scripts/check_msrv.py
echo "== fault injection: kills, a full disk, corrupt pages (scripts/fault_inject.sh)"
./scripts/fault_inject.sh

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

if [ "$(id -u)" -eq 0 ]; then
  echo "== slurm: a 4-task job array + merge on a one-node cluster (scripts/test_slurm.sh)"
  ./scripts/test_slurm.sh
  echo "all checks passed"
else
  echo "== slurm: SKIPPED: not root. The Slurm tier installs Slurm and munge with apt-get and"
  echo "   starts their daemons; run it with: sudo ./scripts/test_slurm.sh"
  echo "all checks passed except the Slurm tier (skipped, see above)"
fi
