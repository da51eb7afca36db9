#!/usr/bin/env bash
# A basin-of-attraction slice of the Fig. 7(a) walk (docs/robustness-gsn.md,
# "A basin-of-attraction slice"): rod a's angular velocity ω_a (offsets
# −40…40 rad/s) against rod b's angle θ_b (offsets −1.2…0.8 rad), 41 × 41
# points, each iterated at most 60 steps on the step map, then the PNG.
# Writes results/robustness/basin_fig7a.{parquet,png,txt}; the .txt is what
# rtw-scan printed (counts and the cost per point).
# Sets up the Python venv (.venv, scripts/requirements.txt) and builds rtw-scan.
. "$(dirname "$0")/lib.sh"

rtw_venv
rtw_build
out=results/robustness
mkdir -p "$out"
# The Fig. 7(a) design, spelled out; every option the default (s = 0.8875).
slice=(basin --length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --phi 0.15
  --x omega_a:-40:40:41 --y theta_b:-1.2:0.8:41 --steps 60 --tol 1e-3)
"$RTW_BIN" "${slice[@]}" --out "$out/basin_fig7a.parquet" >"$out/basin_fig7a.txt"
"$RTW_PY" scripts/basin.py "$out/basin_fig7a.parquet" \
  --title "Basin slice of the Fig. 7(a) walk (L 0.8, ρ 2.5, α 0.125, f_n 3.269, ζ 0.0514, φ 0.15)"
cat "$out/basin_fig7a.txt"
echo "basin: wrote $out/basin_fig7a.{parquet,png,txt}"
