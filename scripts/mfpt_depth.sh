#!/usr/bin/env bash
# How deep an MFPT rtw gives an interval for, and whether the counted MFPT
# holds plain Monte Carlo there (docs/robustness-rough.md, "Mean first-passage
# time", "Deeper MFPTs at a cost"): Fig. 7(a)'s walk on the rough slope of
# SIGMA, two ways, over SEEDS draws each:
#   - the counted MFPT with `robustness.mfpt_batches=BATCHES` (2 880 steps
#     of the walker each), at terrain.seed 0 to SEEDS − 1;
#   - plain Monte Carlo with no cloud and no branching ground: TRIALS trials
#     of at most MAX_STEPS steps (TRIALS × MAX_STEPS at most 10⁷, the most a
#     sample may ask for), each on its own rough slope (terrain.seed
#     k × TRIALS for draw k, so no two draws share a trial).
# Each side's MFPT is its falls over its steps, pooled over the draws, with
# the exact Poisson interval of the count: over the counted steps it is
# 1/fall_rate, the MFPT from the quasi-stationary regime (`mfpt` adds the
# burn-in's transient, within its 60 steps); over every step walked, the
# exponential law's estimate. Each draw is listed too, with `mfpt`.
# The defaults are the deep case: σ = 0.02 m, where the MFPT is near 10⁶
# steps, 3000 batches (the most) and 10 trials of 10⁶ steps, over 5 draws;
# about 35 minutes on 2 cores. `0.03 600 200 50000 1` is the check with many
# falls from one draw (about 2 minutes). Runs two at a time. Writes
# results/robustness/mfpt_depth_SIGMA.md.
#
#   ./scripts/mfpt_depth.sh [SIGMA [BATCHES TRIALS MAX_STEPS [SEEDS]]]
. "$(dirname "$0")/lib.sh"
sigma="${1:-0.02}"
batches="${2:-3000}"
trials="${3:-10}"
cap="${4:-1000000}"
seeds="${5:-5}"
# The only argument rtw-scan does not check itself.
if ! [[ $seeds =~ ^[1-9][0-9]*$ ]]; then
  echo "mfpt_depth: SEEDS: $seeds is invalid: must be a whole number of draws, at least 1" >&2
  exit 2
fi
out="results/robustness/mfpt_depth_$sigma.md"
rtw_venv
rtw_build
tmp=$(mktemp -d)
# On any exit, stop the runs still going (each is rtw-scan under time(1)).
trap 'for j in $(jobs -p); do pkill -P "$j"; done 2>/dev/null; rm -rf "$tmp"' EXIT
fig7a=(--length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15)

# One run: KIND (counted or monte_carlo) at draw K; its JSON and its time.
run() {
  local kind=$1 k=$2 keys
  if [[ $kind == counted ]]; then
    keys=(--set robustness.mfpt=true --set robustness.mfpt_batches="$batches" --set terrain.seed="$k")
  else
    keys=(--set robustness.steps_to_fall=true --set robustness.trials="$trials"
      --set robustness.max_steps="$cap" --set terrain.seed="$((k * trials))")
  fi
  exec /usr/bin/time -f "%e" -o "$tmp/$kind$k.time" "$RTW_BIN" simulate "${fig7a[@]}" \
    --set robustness.sigma="$sigma" "${keys[@]}" --json >"$tmp/$kind$k.json"
}

# Two at a time; a run that fails (rtw-scan refuses a bad argument, naming
# it) stops the script before anything is written.
running=0
for kind in counted monte_carlo; do
  for ((k = 0; k < seeds; k++)); do
    if ((running == 2)); then
      wait -n
      running=$((running - 1))
    fi
    run "$kind" "$k" &
    running=$((running + 1))
  done
done
while ((running > 0)); do
  wait -n
  running=$((running - 1))
done
mkdir -p results/robustness
.venv/bin/python - "$tmp" "$sigma" "$batches" "$trials" "$cap" "$seeds" >"$tmp/depth.md" <<'PY'
import json
import sys
from pathlib import Path

from scipy.stats import chi2

tmp, sigma = Path(sys.argv[1]), sys.argv[2]
batches, trials, cap, seeds = (int(a) for a in sys.argv[3:7])
# A batch: 16 walkers take 60 steps of burn-in, their 32 copies 60 counted
# steps (MFPT_SETTINGS in crates/rtw-model/src/run/mfpt.rs).
counted, taken = batches * 32 * 60, batches * (16 * 60 + 32 * 60)


def read(kind: str, k: int) -> tuple[dict, float]:
    return json.loads((tmp / f"{kind}{k}.json").read_text()), float(
        (tmp / f"{kind}{k}.time").read_text().split()[-1]
    )


def garwood(k: int) -> tuple[float, float]:
    """The exact 95 % interval of a Poisson mean from k events (SciPy's chi2)."""
    lo = 0.0 if k == 0 else chi2.ppf(0.025, 2 * k) / 2
    return lo, chi2.ppf(0.975, 2 * k + 2) / 2


def fmt(v: float | str | None) -> str:
    # simulate --json writes an infinite MFPT as "inf".
    return "∞" if v is None or v in ("inf", float("inf")) else f"{v:,.0f}".replace(",", " ")


def per_fall(steps: float, falls: int) -> str:
    """Steps over falls, and its interval from the count's."""
    lo, hi = garwood(falls)
    mean = steps / falls if falls else None
    return f"{fmt(mean)} [{fmt(steps / hi)}, {fmt(steps / lo if lo > 0 else None)}]"


def draws_of(step: int) -> str:
    """The terrain seeds of the draws, `step` apart."""
    if seeds == 1:
        return "terrain.seed 0"
    return f"terrain.seed 0 to {(seeds - 1) * step}" + (f" by {step}" if step > 1 else "")


draws = []
for k in range(seeds):
    (m, t_m), (mc, t_mc) = read("counted", k), read("monte_carlo", k)
    draws.append(
        {
            "m": m,
            "falls_m": round(m["fall_rate"] * counted),
            "walked": mc["steps_to_fall"] * trials,
            "falls_mc": trials - int(mc["steps_to_fall_censored"]),
            "censored": int(mc["steps_to_fall_censored"]),
            "t_m": t_m,
            "t_mc": t_mc,
        }
    )
falls_m = sum(d["falls_m"] for d in draws)
falls_mc = sum(d["falls_mc"] for d in draws)
walked = sum(d["walked"] for d in draws)
censored = sum(d["censored"] for d in draws)
print(f"# How deep an MFPT has an interval: ./scripts/mfpt_depth.sh {sigma} {batches} {trials} {cap} {seeds}")
print()
print(
    f"Fig. 7(a)'s walk (`rtw-scan simulate --length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 "
    f"--zeta 0.0514 --phi 0.15`) on the rough slope of σ = {sigma} m, 0.8 m patches, "
    f"over {seeds} draw{'s' if seeds > 1 else ''}; each side's MFPT is its falls over its "
    "steps, pooled over the draws, with the exact Poisson interval of the count (over the "
    "counted steps, 1/fall_rate: the MFPT from the quasi-stationary regime, which `mfpt` "
    "extends by the burn-in's transient). Time: the runs' own, each on one core."
)
print()
print("| estimate | MFPT (steps) [95 %] | falls | steps walked | time |")
print("|---|---|---|---|---|")
print(
    f"| counted, `--set robustness.mfpt=true --set robustness.mfpt_batches={batches}`, "
    f"{draws_of(1)}, falls over counted steps | {per_fall(counted * seeds, falls_m)} | "
    f"{falls_m} (in {fmt(counted * seeds)} counted) | {fmt(taken * seeds)} | "
    f"{sum(d['t_m'] for d in draws):.0f} s |"
)
print(
    f"| plain Monte Carlo, `--set robustness.steps_to_fall=true --set robustness.trials={trials} "
    f"--set robustness.max_steps={cap}`, {draws_of(trials)}, "
    f"falls over steps walked | {per_fall(walked, falls_mc)} | {falls_mc} of {trials * seeds} trials "
    f"({censored} walked all {fmt(cap)}) | {fmt(walked)} | {sum(d['t_mc'] for d in draws):.0f} s |"
)
print()
print("## Each draw")
print()
print("| draw | counted: `mfpt` [`mfpt_lo`, `mfpt_hi`] | falls counted | plain Monte Carlo | falls |")
print("|---|---|---|---|---|")
for k, d in enumerate(draws):
    m = d["m"]
    print(
        f"| {k} | {fmt(m['mfpt'])} [{fmt(m['mfpt_lo'])}, {fmt(m.get('mfpt_hi'))}] | {d['falls_m']} | "
        f"{per_fall(d['walked'], d['falls_mc'])} | {d['falls_mc']} of {trials} |"
    )
PY
mv "$tmp/depth.md" "$out"
cat "$out"
