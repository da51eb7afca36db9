#!/usr/bin/env bash
# rtw's engine against heyoka and diffrax on the smallest hybrid systems with
# closed forms, the bouncing ball, the rimless wheel and the impact oscillator
# near grazing (docs/performance.md,
# "Against heyoka and diffrax"): builds hybrid-ode's `peers` example, makes
# .venv-peers (its own venv, apart from .venv: jax and LLVM are heavy and the
# project's scripts need neither) with heyoka and diffrax from the package
# index, runs the three on the same trajectories and tolerances, and writes
# results/bench/peers.md. Not part of scripts/test.sh: it installs jax.
#
#   ./scripts/peers_bench.sh [--quick]      (--quick: n 20, 2 repetitions, to try it)
. "$(dirname "$0")/lib.sh"
n=100
reps=7
out=results/bench/peers.md
if [ "${1:-}" = --quick ]; then
  n=20
  reps=2
  out=${CARGO_TARGET_DIR:-target}/peers-quick.md
fi
tols=1e-6,1e-9,1e-12
load_before=$(cut -d' ' -f1-3 /proc/loadavg)

rtw_build -p hybrid-ode --example peers
python3 -c 'import sys; sys.exit(sys.version_info < (3, 10))' ||
  rtw_die "heyoka and jax need Python >= 3.10, python3 is $(python3 --version 2>&1)"
[ -x .venv-peers/bin/python ] || python3 -m venv .venv-peers
# diffrax 0.7's line (its Event and root finders as used here); heyoka and
# jax as the index serves them, their versions printed on the page.
.venv-peers/bin/pip install --quiet --disable-pip-version-check \
  heyoka "diffrax>=0.7,<0.8" "jax[cpu]" numpy

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"${CARGO_TARGET_DIR:-target}"/release/examples/peers --n "$n" --reps "$reps" --tols "$tols" >"$tmp/rtw.jsonl"
mkdir -p "$(dirname "$out")"
.venv-peers/bin/python scripts/peers_bench.py "$tmp/rtw.jsonl" "$out" --n "$n" --reps "$reps" \
  --tols "$tols" --load-before "$load_before" --notes scripts/peers_notes.md \
  --command "./scripts/peers_bench.sh${1:+ $1}"
echo "wrote $out"
