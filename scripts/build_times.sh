#!/usr/bin/env bash
# The first hour of a fresh clone, as the cold build time of each of the
# three commands a new user runs first (docs/testing.md, "Build times"), in
# the order a user runs them, in a fresh clone of HEAD with an empty target
# directory:
#   1. the main command's build (README): cargo build --release -p rtw-scan
#   2. the Python package as the README installs it, into a venv `v`
#      (pip install ./crates/rtw-py; maturin builds it in target/)
#   3. the test command's builds (scripts/test.sh): clippy, rustdoc, every
#      test binary (cargo test --no-run), and its install of the package
#      into .venv
# Only the builds are timed: maturin, which pip downloads, is fetched
# into both venvs before the clock starts.
# Prints one Markdown row per step, in seconds, and the crates each step
# compiled (a crate compiled again by a later step was not reused).
#   ./scripts/build_times.sh [REV]     # REV: default HEAD; ~20 min on two idle cores
set -euo pipefail
cd "$(dirname "$0")/.."
rev=${1:-HEAD}
root=$(pwd)
work=$(mktemp -d /tmp/rtw-build-times.XXXXXX)
trap 'rm -rf "$work"' EXIT
git clone -q "$root" "$work/rtw"
cd "$work/rtw"
git checkout -q "$rev"
export CARGO_TARGET_DIR="$work/rtw/target"
python3 -m venv v && v/bin/pip install --quiet --disable-pip-version-check maturin==1.16.0
python3 -m venv .venv && .venv/bin/pip install --quiet --disable-pip-version-check maturin==1.16.0
# pip builds with its own isolated environment unless told otherwise; the
# README's user gets the same maturin from PyPI, fetched here beforehand.
n=0
step() {
  local name=$1; shift
  n=$((n + 1))
  local log="$work/step-$n.log" t0 t1
  t0=$(date +%s.%N)
  "$@" > "$log" 2>&1 || { echo "build_times: $name failed:" >&2; tail -20 "$log" >&2; exit 1; }
  t1=$(date +%s.%N)
  local compiled
  compiled=$(grep -cE '^\s*(Compiling|Checking|Documenting)' "$log" || true)
  printf '| %s | %s | %s |\n' "$name" "$(awk "BEGIN { printf \"%.0f\", $t1 - $t0 }")" "$compiled"
}
load=$(cut -d' ' -f1-3 /proc/loadavg)
echo "| step | seconds | crates compiled (or checked) |"
echo "|---|---:|---:|"
step "main: cargo build --release -p rtw-scan" cargo build --release -p rtw-scan
step "python: pip install ./crates/rtw-py (README venv v)" \
  env PATH="$PWD/v/bin:$PATH" v/bin/pip install -v --no-build-isolation --no-deps ./crates/rtw-py
step "test: cargo clippy --workspace --all-targets" cargo clippy --workspace --all-targets --release -- -D warnings
step "test: cargo doc --workspace" env RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps --release
step "test: cargo test --workspace --no-run" cargo test --workspace --release --no-run
step "test: pip install into .venv" \
  env PATH="$PWD/.venv/bin:$PATH" .venv/bin/pip install -v --no-build-isolation --no-deps ./crates/rtw-py
echo
echo "(rev $(git rev-parse --short HEAD), $(nproc) cores, load average before: $load)"
