#!/usr/bin/env bash
# The chain estimator of the MFPT (robustness.mfpt_method = "chain",
# docs/robustness-estimators.md, "The chain method") at Fig. 7(a) against the
# counted estimator's references (run with many batches; their intervals
# in results/robustness/mfpt_chain.md), at σ = 5, 3, 2, 1.5 and 1 cm: each
# command, its mfpt [mfpt_lo, mfpt_hi] and fall_rate, and its wall and CPU
# time (the chain's diagnostics are the library's, Robustness::mfpt_chain:
# `cargo test --release -p rtw-model --test mfpt_chain -- --ignored
# --nocapture` prints them). Writes results/robustness/mfpt_chain-cli.md
# (results/robustness/mfpt_chain.md says where the rest is). The gaits run
# one after another on one thread; on a machine shared with other jobs
# the wall time grows with their load, the CPU time (user + sys) much less.
#
#   ./scripts/mfpt_chain_check.sh [SIGMAS...]
set -euo pipefail
cd "$(dirname "$0")/.."
sigmas=("$@")
[[ ${#sigmas[@]} -gt 0 ]] || sigmas=(0.05 0.03 0.02 0.015 0.01)
cargo build --release -q -p rtw-scan
bin="${CARGO_TARGET_DIR:-target}/release/rtw-scan"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
result=results/robustness/mfpt_chain-cli.md
mkdir -p results/robustness
gait=(--length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15)
{
  echo "# The chain estimator of the MFPT at Fig. 7(a)"
  echo
  echo "Made by \`./scripts/mfpt_chain_check.sh\` on $(date -u +%Y-%m-%d) (load $(cut -d' ' -f1-3 /proc/loadavg))."
  echo "References (the counted estimator, many batches): σ = 5 cm ≈ 150; 3 cm 8 056 [6 839, 9 558];"
  echo "2 cm 822 857 [591 661, 1 181 355]; 1.5 and 1 cm none (beyond counting)."
  echo
  echo "| σ (m) | mfpt | mfpt_lo | mfpt_hi | fall_rate | wall (s) | CPU (s) |"
  echo "|---|---|---|---|---|---|---|"
} >"$tmp/md"
for s in "${sigmas[@]}"; do
  cmd=("$bin" simulate "${gait[@]}" --set robustness.mfpt=true --set robustness.mfpt_method=chain
    --set "robustness.sigma=$s" --json)
  echo "${cmd[*]}" >>"$tmp/commands"
  /usr/bin/time -f "%e %U %S" -o "$tmp/time" "${cmd[@]}" >"$tmp/out.json"
  python3 - "$s" "$tmp/out.json" "$tmp/time" >>"$tmp/md" <<'PY'
import json, sys
s, out, t = sys.argv[1], json.load(open(sys.argv[2])), open(sys.argv[3]).read().split()
g = lambda k: f"{out[k]:.4g}" if isinstance(out.get(k), (int, float)) else str(out.get(k))
print(f"| {s} | {g('mfpt')} | {g('mfpt_lo')} | {g('mfpt_hi')} | {g('fall_rate')} | "
      f"{t[0]} | {float(t[1]) + float(t[2]):.1f} |")
PY
done
{
  echo
  echo "Commands:"
  echo
  sed 's/^/    /' "$tmp/commands"
} >>"$tmp/md"
cp "$tmp/md" "$result"
cat "$result"
