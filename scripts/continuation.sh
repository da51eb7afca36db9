#!/usr/bin/env bash
# The continuation diagrams of docs/continuation.md -> results/continuation/:
#   1. the Fig. 7(a) walk continued in φ, stable and unstable, its bifurcations,
#      the period-2 branch born at its period doubling, and that period doubling
#      continued in (φ, f_n): rtw-scan continuation --curve fn
#   2. the brute-force check of that curve: configs/continuation-plane.toml (every
#      grid point of the (φ, f_n) plane simulated, its limit cycle solved),
#      compared column by column (scripts/continuation.py plane --check fails
#      the script if they disagree beyond the grid's resolution)
#   3. the s = 0 skip on a steep slope, whose feet touch and go, continued in φ
#      on the touch-and-go section (--section touch-and-go)
#   4. the figures (scripts/continuation.py) and results/continuation/summary.md
# Uses results/bifurcation/phi-fig7a.parquet (./scripts/bifurcation.sh) for the
# attractor drawn under the diagram. Both continuations run at once (2 cores).
# Every figure's title names the model of the data it draws, read from the
# data's rtw.variant (scripts/continuation.py), never from today's template.
. "$(dirname "$0")/lib.sh"
out=results/continuation
mkdir -p "$out"
walk=(continuation --param phi --from 0.02 --to 0.35 --curve fn --curve-from 2.9 --curve-to 3.9)
skip=(continuation --param phi --phi 0.34 --from 0.30 --to 0.38 --set strings.rest_length_ratio=0
      --section touch-and-go)
# REPORT_ONLY=1 remakes the figures, the check and summary.md from the committed
# files (as in continuation_segments.sh).
if [ -z "${REPORT_ONLY:-}" ]; then
  rtw_build
  "$RTW_BIN" "${walk[@]}" --out "$out/phi-fig7a.parquet" --force >"$out/phi-fig7a.log" &
  a=$!
  "$RTW_BIN" "${skip[@]}" --out "$out/phi-s0-touch-and-go.parquet" --force >"$out/phi-s0.log" &
  b=$!
  wait "$a"
  wait "$b"
  # The walk continued through its mode-sequence changes (Fig. S3), in its own
  # script (the longest part: SKIP_SEGMENTS=1 leaves it out).
  [ -n "${SKIP_SEGMENTS:-}" ] || ./scripts/continuation_segments.sh
  rm -rf "$out/plane"
  "$RTW_BIN" run configs/continuation-plane.toml --out "$out/plane" --quiet >/dev/null
fi

py=$RTW_PY
$py scripts/continuation.py diagram "$out/phi-fig7a.parquet" --sweep results/bifurcation/phi-fig7a.parquet \
  --title "The Fig. 7(a) walk continued in φ"
$py scripts/continuation.py diagram "$out/phi-s0-touch-and-go.parquet" \
  --title "The s = 0 skip continued in φ on the touch-and-go section (from φ = 0.34)"
plane=$($py scripts/continuation.py plane "$out/phi-fig7a.parquet" "$out/plane/samples.parquet" --check \
  --title "The walk's period-doubling boundary in (φ, f_n) over the brute-force scan")

{
  echo "# Continuation diagrams"
  echo
  echo "Made by \`./scripts/continuation.sh\`. Files per diagram: NAME.parquet (branch points),"
  echo "NAME.special.parquet (bifurcations, branch ends), NAME.curve.parquet (two-parameter curves), NAME.png."
  echo
  echo "## The Fig. 7(a) walk in φ at the default model: phi-fig7a.png"
  echo
  echo "\`rtw-scan ${walk[*]}\`"
  echo
  cat "$out/phi-fig7a.md"
  echo
  echo "## Its period-doubling curve in (φ, f_n) against the brute-force scan, default model: phi-fig7a.plane.png"
  echo
  echo "\`rtw-scan run configs/continuation-plane.toml\` (in results/continuation/plane/: period and Floquet multipliers of every grid point's"
  echo "limit cycle, each run from its standing start); per column of f_n, every φ where the continued curves"
  echo "cross it (the period-1 walk's stability flips at each), where the scan's runs settle on a stable period-1"
  echo "or period-2 walk, and whether they agree (\`scripts/continuation.py plane --check\`: no stable period-1"
  echo "walk where continuation has it unstable, except past an open crossing, on a curve whose continuation stopped"
  echo "unresolved within a column; a period-2 walk where it has the period-1 walk stable is a coexisting attractor,"
  echo "reported; in the one-parameter diagram's own column, one of the two walks between the band where both are"
  echo "stable and the doubling):"
  echo
  echo "$plane"
  echo
  echo "## The s = 0 skip on the touch-and-go section: phi-s0-touch-and-go.png"
  echo
  echo "\`rtw-scan ${skip[*]}\`"
  echo
  cat "$out/phi-s0-touch-and-go.md"
} >"$out/summary.md"
rm -f "$out/phi-fig7a.log" "$out/phi-s0.log"
echo "continuation: wrote $out/summary.md and the diagrams"
