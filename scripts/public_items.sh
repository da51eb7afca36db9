#!/usr/bin/env bash
# Counts the public items of rtw-model and hybrid-ode from fresh rustdoc
# output (the method is in scripts/public_items.py and docs/architecture.md).
# Usage: scripts/public_items.sh [--list]
set -euo pipefail
cd "$(dirname "$0")/.."
doc="${CARGO_TARGET_DIR:-target}/doc"
# Stale pages of items made private would otherwise be counted.
rm -rf "$doc/rtw_model" "$doc/hybrid_ode"
cargo doc --quiet --no-deps -p rtw-model -p hybrid-ode
python3 scripts/public_items.py "$@" --doc "$doc" rtw_model hybrid_ode
