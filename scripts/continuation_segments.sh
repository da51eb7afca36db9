#!/usr/bin/env bash
# The Fig. S3 story as a continuation diagram -> results/continuation/:
#   the Fig. 7(a) walk continued in φ over [0.05, 0.3] through the changes of its
#   mode sequence (rtw-scan continuation --through), for L = 0.7, 0.8 and 0.9;
#   each segment's end located and named (grazing, corner, gait lost, range end);
#   the figure phi-segments.png (scripts/continuation_segments.py diagram), and the
#   L = 0.8 segments checked against the attractor sweep
#   results/bifurcation/phi-fig7a.parquet (./scripts/bifurcation.sh): same label,
#   period and step frequency (relative 1e-3) wherever both are stable; fails the
#   script if they disagree. Writes results/continuation/segments.md.
# Called by ./scripts/continuation.sh; runs the three lengths at once (each
# continues its directions two at a time, the period-2 ones too), at the default model (as
# the attractor sweep); the figure's title names the model read from the files' rtw.variant.
. "$(dirname "$0")/lib.sh"
out=results/continuation
mkdir -p "$out"
through=(continuation --param phi --from 0.05 --to 0.3 --through 8)
run() { "$RTW_BIN" "${through[@]}" --length "$1" --out "$out/phi-segments-L$1.parquet" --force >"$out/phi-segments-L$1.log"; }
# REPORT_ONLY=1 remakes the figure and segments.md from the committed files.
if [ -z "${REPORT_ONLY:-}" ]; then
  rtw_build
  run 0.7 &
  a=$!
  run 0.8 &
  b=$!
  run 0.9 &
  c=$!
  wait "$a"
  wait "$b"
  wait "$c"
fi

py=$RTW_PY
$py scripts/continuation_segments.py diagram "$out"/phi-segments-L0.{7,8,9}.segments.json \
  --sweep results/bifurcation/phi-fig7a.parquet --out "$out/phi-segments.png" \
  --title "The Fig. 7(a) walk continued in φ through its mode-sequence changes (rtw-scan ${through[*]})"
check=$($py scripts/continuation_segments.py check "$out/phi-segments-L0.8.segments.json" \
  results/bifurcation/phi-fig7a.parquet)
{
  echo "# The Fig. S3 story: the walk continued through its mode-sequence changes"
  echo
  echo "Made by \`./scripts/continuation_segments.sh\`: \`rtw-scan ${through[*]} --length L\` for L = 0.7, 0.8, 0.9"
  echo "(files results/continuation/phi-segments-L*.{parquet,special.parquet,segments.json,md}), figure phi-segments.png."
  echo
  for L in 0.7 0.8 0.9; do
    echo "## L = $L"
    sed -n '/^Through the changes of mode sequence/,$p' "$out/phi-segments-L$L.md"
    echo
  done
  echo "## L = 0.8 against the attractor sweep (results/bifurcation/phi-fig7a.parquet)"
  echo
  echo "Where a segment and the sweep are both stable, at the sweep's values inside the segment:"
  echo
  echo "$check"
} >"$out/segments.md"
rm -f "$out"/phi-segments-L*.log
echo "continuation_segments: wrote $out/segments.md and phi-segments.png"
