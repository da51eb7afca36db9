#!/usr/bin/env bash
# The cost of the robustness measures: the paper scan plain, with
# robustness.step_down=true, and with step_down and gsn, one thread each, in
# one run (docs/robustness-step-down.md, "Cost"). Writes into a temporary directory only.
. "$(dirname "$0")/lib.sh"
rtw_build
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
t0=$(date +%s.%N)
"$RTW_BIN" run configs/paper.toml --out "$tmp/plain" --threads 1 --quiet >/dev/null
t1=$(date +%s.%N)
"$RTW_BIN" run configs/paper.toml --out "$tmp/step" --threads 1 --quiet --set robustness.step_down=true >/dev/null
t2=$(date +%s.%N)
"$RTW_BIN" run configs/paper.toml --out "$tmp/gsn" --threads 1 --quiet --set robustness.step_down=true \
    --set robustness.gsn=true >/dev/null
t3=$(date +%s.%N)
python3 - "$t0" "$t1" "$t2" "$t3" <<'PY'
import sys
t0, t1, t2, t3 = map(float, sys.argv[1:])
plain, step, both = t1 - t0, t2 - t1, t3 - t2
print(f"plain scan {plain:.2f} s, with step_down {step:.2f} s (ratio {step / plain:.1f}), "
      f"with step_down and gsn {both:.2f} s (ratio {both / plain:.1f}; gsn alone {(both - step) / plain:.1f})")
PY
