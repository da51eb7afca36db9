#!/usr/bin/env bash
# Two revisions' builds of the workspace's own crates, paired: one fresh
# clone, its dependencies built once, then ROUNDS rounds of A then B, each
# checking out its revision, removing the workspace crates' artifacts
# (cargo clean -p for each member), building the main command and then the
# test command's test binaries, each timed (wall, and CPU of every rustc).
# The dependencies are the same build for both, so what differs is the
# workspace's own compile; pairing keeps the ratio when the machine's speed
# drifts (docs/testing.md, "Build times"; one-off cold numbers per step:
# scripts/build_times.sh). Prints a Markdown table of the rounds and the
# median (and range) of the ratios A/B taken round by round.
#   ./scripts/build_pair.sh REV_A REV_B [ROUNDS]   # ~5 min a round on two idle cores
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: build_pair.sh REV_A REV_B [ROUNDS]" >&2; exit 2; }
a=$1 b=$2 rounds=${3:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d /tmp/rtw-build-pair.XXXXXX)
trap 'rm -rf "$work"' EXIT
git clone -q "$root" "$work/rtw"
cd "$work/rtw"
export CARGO_TARGET_DIR="$work/target"
members=$(cargo metadata --no-deps --format-version 1 | python3 -c \
  'import json, sys; print(" ".join("-p " + p["name"] for p in json.load(sys.stdin)["packages"]))')
git checkout -q "$a" && cargo build --release -p rtw-scan -q && cargo test --workspace --release --no-run -q 2>/dev/null
git checkout -q "$b" && cargo build --release -p rtw-scan -q && cargo test --workspace --release --no-run -q 2>/dev/null
timed() { # COMMAND...: prints its wall and CPU seconds
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$work/cpu" "$@" >/dev/null 2>&1
  t1=$(date +%s.%N)
  awk -v w="$(echo "$t1 - $t0" | bc)" '{ printf "%.1f %.1f\n", w, $1 + $2 }' "$work/cpu"
}
echo "| round | revision | main build wall (s) | main build CPU (s) | test build wall (s) | test build CPU (s) |"
echo "|---:|---|---:|---:|---:|---:|"
for r in $(seq "$rounds"); do
  for rev in "$a" "$b"; do
    git checkout -q "$rev"
    # shellcheck disable=SC2086
    cargo clean --release $members -q
    read -r mw mc < <(timed cargo build --release -p rtw-scan)
    read -r tw tc < <(timed cargo test --workspace --release --no-run)
    echo "| $r | $rev | $mw | $mc | $tw | $tc |"
    echo "$rev $mw $mc $tw $tc" >>"$work/all"
  done
done
python3 - "$work/all" "$a" "$b" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
a = [list(map(float, r[1:])) for r in rows if r[0] == sys.argv[2]]
b = [list(map(float, r[1:])) for r in rows if r[0] == sys.argv[3]]
names = ["main build wall", "main build CPU", "test build wall", "test build CPU"]
print()
print(f"Medians over {len(a)} rounds of {sys.argv[2]}/{sys.argv[3]}, round by round:",
      "; ".join(f"{n} {statistics.median(x[i] / y[i] for x, y in zip(a, b)):.2f}"
                f" ({min(x[i] / y[i] for x, y in zip(a, b)):.2f}-{max(x[i] / y[i] for x, y in zip(a, b)):.2f})"
                for i, n in enumerate(names)) + ".")
PY
