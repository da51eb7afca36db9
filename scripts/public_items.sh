#!/usr/bin/env bash
# Counts the public items of every library crate from fresh rustdoc
# output (the method is in scripts/public_items.py and docs/architecture.md).
# Usage: scripts/public_items.sh [--list]
set -euo pipefail
cd "$(dirname "$0")/.."
doc="${CARGO_TARGET_DIR:-target}/doc"
# Stale pages of items made private would otherwise be counted.
crates=(hybrid_ode rtw_model rtw_engine rtw_studies rtw_scan)
for c in "${crates[@]}"; do rm -rf "${doc:?}/$c"; done
cargo doc --quiet --no-deps -p hybrid-ode -p rtw-model -p rtw-engine -p rtw-studies -p rtw-scan
python3 scripts/public_items.py "$@" --doc "$doc" "${crates[@]}"
