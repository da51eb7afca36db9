#!/usr/bin/env bash
# The "Hot path" table of docs/performance.md: instruction counts (callgrind, repeatable on
# a shared machine) of one 20 s run at Fig. 7(a) at the default model, for the default
# method (DP5(4) at rtol 1e-4) and DOP853 at rtol 1e-10, split by
# scripts/hot_path.py. Needs valgrind. Usage: scripts/hot_path.sh [OUTDIR]
. "$(dirname "$0")/lib.sh"
out=${1:-$(mktemp -d)}
mkdir -p "$out"
rtw_build -p rtw-model --example profile
for run in "dp54 1e-4" "dop853 1e-10"; do
  set -- $run
  valgrind --tool=callgrind --callgrind-out-file="$out/$1" \
    target/release/examples/profile default "$1" "$2" 1 2>/dev/null >"$out/$1.work"
done
(cd "$out" && python3 "$OLDPWD/scripts/hot_path.py" dp54 dop853)
