#!/usr/bin/env bash
# How deep an MFPT rtw gives an interval for, and whether the counted MFPT
# holds plain Monte Carlo there (docs/robustness.md, "Mean first-passage
# time", "Deeper MFPTs at a cost"): Fig. 7(a)'s walk on the rough slope of
# SIGMA, two ways at once on the 2 cores:
#   - the counted MFPT with `robustness.mfpt_batches=BATCHES` (2 880 steps
#     of the walker each);
#   - plain Monte Carlo with no cloud and no branching ground: TRIALS trials
#     of at most MAX_STEPS steps (TRIALS × MAX_STEPS at most 10⁷, the most a
#     sample may ask for), each on its own rough slope, its fall rate the
#     falls over all the steps walked (the exponential law's estimate, with
#     the exact Poisson interval of the count).
# The defaults are the deep case: σ = 0.02 m, where the MFPT is about 10⁶
# steps, 3000 batches (the most), 10 trials of 10⁶ steps; about 10 minutes
# on 2 cores. `0.03 600 200 50000` is the check with many falls on both
# sides (about 2 minutes). Writes results/robustness/mfpt_depth_SIGMA.md.
#
#   ./scripts/mfpt_depth.sh [SIGMA [BATCHES TRIALS MAX_STEPS]]
set -euo pipefail
cd "$(dirname "$0")/.."
sigma="${1:-0.02}"
batches="${2:-3000}"
trials="${3:-10}"
cap="${4:-1000000}"
out="results/robustness/mfpt_depth_$sigma.md"
./scripts/venv.sh
cargo build --release -q -p rtw-scan
bin="${CARGO_TARGET_DIR:-target}/release/rtw-scan"
tmp=$(mktemp -d)
# On any exit, stop the other run too (rtw-scan runs under time(1)).
trap 'for j in $(jobs -p); do pkill -P "$j"; done 2>/dev/null; rm -rf "$tmp"' EXIT
fig7a=(--length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15)
/usr/bin/time -f "%e" -o "$tmp/mfpt.time" "$bin" simulate "${fig7a[@]}" \
  --set robustness.mfpt=true --set robustness.sigma="$sigma" --set robustness.mfpt_batches="$batches" \
  --json >"$tmp/mfpt.json" &
counted_run=$!
/usr/bin/time -f "%e" -o "$tmp/mc.time" "$bin" simulate "${fig7a[@]}" \
  --set robustness.steps_to_fall=true --set robustness.sigma="$sigma" --set robustness.trials="$trials" \
  --set robustness.max_steps="$cap" --json >"$tmp/mc.json" &
monte_carlo_run=$!
# Each run's own status: rtw-scan refuses a bad argument, naming it, and
# then nothing is written.
wait "$counted_run"
wait "$monte_carlo_run"
mkdir -p results/robustness
.venv/bin/python - "$tmp" "$sigma" "$batches" "$trials" "$cap" >"$tmp/depth.md" <<'PY' 
import json
import sys
from pathlib import Path

from scipy.stats import chi2

tmp, sigma = Path(sys.argv[1]), sys.argv[2]
batches, trials, cap = (int(a) for a in sys.argv[3:6])
m = json.loads((tmp / "mfpt.json").read_text())
mc = json.loads((tmp / "mc.json").read_text())
t_m = float((tmp / "mfpt.time").read_text().split()[-1])
t_mc = float((tmp / "mc.time").read_text().split()[-1])
# A batch: 16 walkers take 60 steps of burn-in, their 32 copies 60 counted
# steps (MFPT_SETTINGS in crates/rtw-model/src/run/mfpt.rs).
counted, taken = batches * 32 * 60, batches * (16 * 60 + 32 * 60)


def garwood(k: int) -> tuple[float, float]:
    """The exact 95 % interval of a Poisson mean from k events (SciPy's chi2)."""
    lo = 0.0 if k == 0 else chi2.ppf(0.025, 2 * k) / 2
    return lo, chi2.ppf(0.975, 2 * k + 2) / 2


def fmt(v: float | None) -> str:
    return "∞" if v is None or v == float("inf") else f"{v:,.0f}".replace(",", " ")


falls_m = round(m["fall_rate"] * counted)
walked = mc["steps_to_fall"] * trials
falls_mc = trials - int(mc["steps_to_fall_censored"])
k_lo, k_hi = garwood(falls_mc)
print(f"# How deep an MFPT has an interval: ./scripts/mfpt_depth.sh {sigma} {batches} {trials} {cap}")
print()
print(
    f"Fig. 7(a)'s walk (`rtw-scan simulate --length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 "
    f"--zeta 0.0514 --phi 0.15`) on the rough slope of σ = {sigma} m, 0.8 m patches, "
    "terrain.seed 0, the two runs side by side on 2 cores."
)
print()
print("| estimate | MFPT (steps) [95 %] | falls | steps walked | wall time |")
print("|---|---|---|---|---|")
print(
    f"| counted, `--set robustness.mfpt=true --set robustness.mfpt_batches={batches}` | "
    f"{fmt(m['mfpt'])} [{fmt(m['mfpt_lo'])}, {fmt(m.get('mfpt_hi'))}] | {falls_m} "
    f"(in {fmt(counted)} counted) | {fmt(taken)} | {t_m:.0f} s |"
)
print(
    f"| plain Monte Carlo, `--set robustness.steps_to_fall=true --set robustness.trials={trials} "
    f"--set robustness.max_steps={cap}`, falls over steps walked | "
    f"{fmt(walked / falls_mc if falls_mc else None)} [{fmt(walked / k_hi)}, "
    f"{fmt(walked / k_lo if k_lo > 0 else None)}] | {falls_mc} of {trials} trials "
    f"({int(mc['steps_to_fall_censored'])} walked all {fmt(cap)}) | {fmt(walked)} | {t_mc:.0f} s |"
)
PY
mv "$tmp/depth.md" "$out"
cat "$out"
