#!/usr/bin/env bash
# Peak memory of a scan against its sample count (docs/performance.md, "Scaling and memory").
#
#   scripts/mem_bench.sh [SIZE ...]      # default: 1k 10k 100k (configs/bench/mem-SIZE.toml)
#
# For each of 3 interleaved rounds and each size: `rtw-scan run` (the whole
# scan: chunks, merge, summary) and `rtw-scan summary` on its output, both
# under `/usr/bin/time -f "%e %U %M"`. Prints a Markdown table of the medians
# of peak RSS (MB = 1024 kB: %M counts KiB) and wall time. Set RTW_SCAN to measure another
# binary (default: target/release/rtw-scan, built first).
. "$(dirname "$0")/lib.sh"
sizes=("$@")
[ ${#sizes[@]} -eq 0 ] && sizes=(1k 10k 100k)
bin=${RTW_SCAN:-$RTW_BIN}
if [ -z "${RTW_SCAN:-}" ]; then
  rtw_build
fi
[ -x /usr/bin/time ] || rtw_die "needs /usr/bin/time (Debian: apt-get install time)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
rounds=3
for r in $(seq $rounds); do
  for n in "${sizes[@]}"; do
    out=$tmp/mem-$n
    rm -rf "$out"
    /usr/bin/time -o "$tmp/t" -f "%e %U %M" "$bin" run "configs/bench/mem-$n.toml" --out "$out" >/dev/null 2>&1
    echo "run $n $(cat "$tmp/t")" >>"$tmp/all"
    /usr/bin/time -o "$tmp/t" -f "%e %U %M" "$bin" summary "$out/samples.parquet" >/dev/null 2>&1
    echo "summary $n $(cat "$tmp/t")" >>"$tmp/all"
  done
done
# Median of the 3 values in column $col for rows matching (what, size).
median() {
  awk -v w="$1" -v n="$2" -v c="$3" '$1 == w && $2 == n { print $c }' "$tmp/all" | sort -g | sed -n 2p
}
echo "| samples | run: peak RSS MB | run: wall s | summary: peak RSS MB |"
echo "|---:|---:|---:|---:|"
for n in "${sizes[@]}"; do
  awk -v n="$n" -v rss="$(median run "$n" 5)" -v wall="$(median run "$n" 3)" \
    -v srss="$(median summary "$n" 5)" \
    'BEGIN { printf "| %s | %.1f | %.2f | %.1f |\n", n, rss / 1024, wall, srss / 1024 }'
done
