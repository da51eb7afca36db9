#!/usr/bin/env bash
# The Slurm test (issue 6), run by scripts/test.sh: a real one-node Slurm
# cluster on this machine (scripts/slurm/local-cluster.sh: Debian's slurmctld,
# slurmd and munge), a 4-task array of configs/smoke.toml through
# scripts/slurm/scan-array.sbatch, the merge job chained with
# --dependency=afterok, and the merged samples.parquet compared value by value
# with a single-machine run of the same config (scripts/compare_scans.py;
# also the parts read directly with polars.scan_parquet("DIR/part-*.parquet")).
#
# If Slurm cannot be installed or started, this fails loudly (exit 1); it
# never passes without having run the jobs. The daemons it started are
# stopped on exit, whatever happens.
#
# Usage: scripts/test_slurm.sh [CONFIG]   (default configs/smoke.toml)
set -euo pipefail
cd "$(dirname "$0")/.."
config=${1:-configs/smoke.toml}
shards=4
timeout_s=600
started=$(date +%s)

fail() {
  echo "test_slurm: FAILED: $*" >&2
  exit 1
}

cargo build --release -q -p rtw-scan
export RTW_SCAN=$PWD/target/release/rtw-scan
if [ ! -x .venv/bin/python ]; then
  python3 -m venv .venv
fi
.venv/bin/pip install --quiet --disable-pip-version-check -r scripts/requirements.txt

work=$(mktemp -d)
state=$work/slurm
cleanup() {
  scripts/slurm/local-cluster.sh stop "$state" || true
  rm -rf "$work"
}
trap cleanup EXIT

scripts/slurm/local-cluster.sh start "$state" || fail "Slurm did not start on this machine (see above)"
export SLURM_CONF=$state/slurm.conf

out=$work/sharded
# The two commands of the README's "On a cluster" (plus log locations).
jid=$(sbatch --parsable --array=0-$((shards - 1)) --cpus-per-task=1 \
  --output="$work/task-%a.out" scripts/slurm/scan-array.sbatch "$config" "$out") ||
  fail "sbatch of the array was refused"
echo "test_slurm: array job $jid ($shards tasks) submitted"
# --wait: returns when the merge job ends, with its exit code. A failed array
# task makes the dependency impossible and Slurm cancels the merge
# (DependencyParameters=kill_invalid_depend), so this cannot hang; timeout
# bounds it anyway.
merge_rc=0
timeout "$timeout_s" sbatch --wait --parsable --dependency=afterok:"$jid" \
  --output="$work/merge.out" scripts/slurm/merge.sbatch "$out" || merge_rc=$?
for f in "$work"/task-*.out "$work"/merge.out; do
  [ -f "$f" ] && { echo "----- $(basename "$f")"; cat "$f"; }
done
if [ "$merge_rc" -ne 0 ]; then
  squeue || true
  scontrol show job "$jid" || true
  [ "$merge_rc" -eq 124 ] && fail "the jobs did not finish within $timeout_s s"
  fail "the merge job failed or was cancelled (exit $merge_rc)"
fi
for k in $(seq 0 $((shards - 1))); do
  [ -f "$out/part-$k.parquet" ] || fail "part-$k.parquet was not written"
  grep -q "shard $k/$shards" "$work/task-$k.out" || fail "task $k did not run shard $k/$shards"
done
[ -f "$out/samples.parquet" ] && [ -f "$out/summary.md" ] || fail "merge wrote no samples.parquet/summary.md"

"$RTW_SCAN" run "$config" --out "$work/single" --threads 2 >/dev/null 2>&1 ||
  fail "the single-machine run failed"
.venv/bin/python scripts/compare_scans.py "$out/samples.parquet" "$work/single/samples.parquet" ||
  fail "the merged file differs from the single-machine run"
.venv/bin/python scripts/compare_scans.py "$out/part-*.parquet" "$work/single/samples.parquet" ||
  fail "the parts, read with polars.scan_parquet, differ from the single-machine run"

echo "test_slurm: passed: $shards Slurm array tasks + merge give the single-machine rows ($(($(date +%s) - started)) s)"
