#!/usr/bin/env bash
# Builds the scan report's Plotly.js: plotly.js with only the trace types the
# page draws (scripts/plotly_bundle/entry.js), about half the full bundle's
# bytes and load time (docs/report.md), and checks it against the committed
# crates/rtw-py/python/rtw/report_assets/plotly-rtw.min.js and its .sha256.
#
#   ./scripts/plotly_bundle.sh           # rebuild, fail unless identical to the committed file
#   ./scripts/plotly_bundle.sh --write   # rebuild and replace it (after changing the pins or entry.js)
#
# Reproducible: the npm packages (plotly.js 4.1.1, esbuild and plotly.js's own
# esbuild plugins) are pinned, each with its sha512, in
# scripts/plotly_bundle/package-lock.json, installed by `npm ci` into a
# temporary directory (nothing runs at install: --ignore-scripts) and built
# with plotly.js's esbuild settings. Needs node and npm (Node 20 or later).
. "$(dirname "$0")/lib.sh"
ASSET=crates/rtw-py/python/rtw/report_assets/plotly-rtw.min.js
write=0
case "${1:-}" in
  --write) write=1 ;;
  "") ;;
  *) echo "plotly_bundle.sh: unknown option ${1}: use --write or nothing" >&2; exit 2 ;;
esac
rtw_need node npm
tmp=$(mktemp -d /tmp/rtw-plotly-bundle.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
cp scripts/plotly_bundle/{package.json,package-lock.json,entry.js,build.js} "$tmp"/
(cd "$tmp" && npm ci --ignore-scripts --no-audit --no-fund --loglevel=error && node build.js plotly-rtw.min.js)
if [ "$write" = 1 ]; then
  cp "$tmp/plotly-rtw.min.js" "$ASSET"
  (cd "$(dirname "$ASSET")" && sha256sum plotly-rtw.min.js > plotly-rtw.min.js.sha256)
  echo "wrote $ASSET ($(wc -c < "$ASSET") bytes)"
else
  (cd "$(dirname "$ASSET")" && sha256sum -c plotly-rtw.min.js.sha256 >/dev/null) ||
    { echo "plotly_bundle.sh: $ASSET does not match its .sha256" >&2; exit 1; }
  cmp "$tmp/plotly-rtw.min.js" "$ASSET" ||
    { echo "plotly_bundle.sh: the rebuilt bundle differs from $ASSET" >&2; exit 1; }
  echo "$ASSET: rebuilt identical ($(cut -c1-16 "$ASSET.sha256")…)"
fi
