#!/usr/bin/env bash
# The bifurcation diagrams of results/bifurcation/ (how the gait changes with
# the slope): φ swept over
# [0.02, 0.35] (121 values) at the Fig. 7(a) point with continuation on the
# step map, for the default model (its s read from configs/template.toml, which
# states every default) and for s = 0 (every other option the default's), run
# side by side, then the plots and summary.md.
# Sets up the Python venv (.venv, scripts/requirements.txt, the package rtw) and builds rtw-scan.
. "$(dirname "$0")/lib.sh"

rtw_install
out=results/bifurcation
mkdir -p "$out"
# The default strings' natural length, for the summary's heading (crates/rtw-scan-test/tests/it/template.rs
# checks that the template sets every key to its default; scripts/check_default_model.py
# that the data called default is at it). The figures' titles name the model read from the data.
s=$(sed -n 's/^strings\.rest_length_ratio = //p' configs/template.toml)

sweep=(bifurcation --param phi --from 0.02 --to 0.35 --points 121 --transient 200 --record 48)
# REPORT_ONLY=1 remakes the figures and summary.md from the committed files.
if [ -z "${REPORT_ONLY:-}" ]; then
  rtw_build
  # The two sweeps are independent (continuation is sequential within each).
  "$RTW_BIN" "${sweep[@]}" --out "$out/phi-fig7a.parquet" >/dev/null 2>"$out/phi-fig7a.log" &
  a=$!
  "$RTW_BIN" "${sweep[@]}" --set strings.rest_length_ratio=0 --out "$out/phi-fig7a-s0.parquet" >/dev/null 2>"$out/phi-fig7a-s0.log" &
  b=$!
  wait "$a"
  wait "$b"
fi

py=$RTW_PY
$py scripts/bifurcation.py "$out/phi-fig7a.parquet" \
  --title "φ sweep at Fig. 7(a) (L 0.8, ρ 2.5, α 0.125, f_n 3.269, ζ 0.0514), default model"
$py scripts/bifurcation.py "$out/phi-fig7a-s0.parquet" \
  --title "φ sweep at Fig. 7(a), s = 0 (zero-rest-length strings, every other option the default's)"

{
  echo "# Bifurcation diagrams in φ at the Fig. 7(a) point"
  echo
  echo "Made by \`./scripts/bifurcation.sh\`: \`rtw-scan ${sweep[*]} [--set strings.rest_length_ratio=0] --out results/bifurcation/NAME.parquet\`,"
  echo "then \`scripts/bifurcation.py\` for the PNGs. Per value: NAME.parquet; per recorded step: NAME.steps.parquet."
  echo
  echo "## Default model (s = $s): phi-fig7a.png"
  echo
  cat "$out/phi-fig7a.md"
  echo
  echo "## s = 0: phi-fig7a-s0.png"
  echo
  cat "$out/phi-fig7a-s0.md"
} >"$out/summary.md"
rm -f "$out/phi-fig7a.log" "$out/phi-fig7a-s0.log"
echo "bifurcation: wrote $out/{phi-fig7a,phi-fig7a-s0}.{parquet,steps.parquet,md,png} and $out/summary.md"
