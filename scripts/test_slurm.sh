#!/usr/bin/env bash
# The Slurm test, run by scripts/test.sh, so that sharded scans on a cluster
# give the single machine's rows: a real one-node Slurm
# cluster on this machine (scripts/slurm/local-cluster.sh: Debian's slurmctld,
# slurmd and munge), a 4-task array of configs/smoke.toml through
# scripts/slurm/scan-array.sbatch, the merge job chained with
# --dependency=afterok, and the merged samples.parquet compared value by value
# with a single-machine run of the same config (scripts/compare_scans.py;
# also the parts read directly with polars.scan_parquet("DIR/part-*.parquet")).
# Then a lost shard is rerun alone and merged again, and a failing array task
# must make Slurm cancel the merge job.
#
# If Slurm cannot be installed or started, this fails loudly (exit 1); it
# never passes without having run the jobs. The daemons it started are
# stopped on exit, whatever happens.
#
# Usage: scripts/test_slurm.sh [CONFIG]   (default configs/smoke.toml)
. "$(dirname "$0")/lib.sh"
if [ "$(id -u)" -ne 0 ]; then
  echo "test_slurm: needs root (it installs Slurm and munge with apt-get and starts their daemons): sudo $0" >&2
  exit 1
fi
config=${1:-configs/smoke.toml}
shards=4
timeout_s=600
started=$(date +%s)

fail() {
  echo "test_slurm: FAILED: $*" >&2
  exit 1
}

# submit_wait OUTPUT_FILE SBATCH_ARGS...: submits a job, waits for its end
# (polling squeue, bounded by timeout_s), prints its final state. (sbatch
# --wait polls more slowly, and exits 0 for a job that Slurm cancelled
# before it ran.)
submit_wait() {
  local log=$1 id t0
  shift
  id=$(sbatch --parsable --output="$log" "$@") || fail "sbatch $* was refused"
  t0=$(date +%s)
  while [ -n "$(squeue -h -j "$id" 2>/dev/null)" ]; do
    if [ $(($(date +%s) - t0)) -gt "$timeout_s" ]; then
      squeue -t all >&2 || true
      fail "job $id did not finish within $timeout_s s"
    fi
    sleep 0.2
  done
  scontrol show job "$id" | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p'
}

rtw_build
export RTW_SCAN=$(cd "$(dirname "$RTW_BIN")" && pwd)/rtw-scan
rtw_venv

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
# The two commands of docs/cluster.md (plus log locations).
jid=$(sbatch --parsable --array=0-$((shards - 1)) --cpus-per-task=1 \
  --output="$work/task-%a.out" scripts/slurm/scan-array.sbatch "$config" "$out") ||
  fail "sbatch of the array was refused"
echo "test_slurm: array job $jid ($shards tasks) submitted"
# A failed array task makes the merge's dependency impossible and Slurm
# cancels the merge (DependencyParameters=kill_invalid_depend), so this
# cannot hang; the timeout bounds it anyway.
merge_state=$(submit_wait "$work/merge.out" --dependency=afterok:"$jid" scripts/slurm/merge.sbatch "$out")
for f in "$work"/task-*.out "$work"/merge.out; do
  [ -f "$f" ] && { echo "----- $(basename "$f")"; cat "$f"; }
done
if [ "$merge_state" != COMPLETED ]; then
  squeue -t all || true
  fail "the merge job ended $merge_state, not COMPLETED"
fi
for k in $(seq 0 $((shards - 1))); do
  [ -f "$out/part-$k.parquet" ] || fail "part-$k.parquet was not written"
  grep -q "shard $k/$shards" "$work/task-$k.out" || fail "task $k did not run shard $k/$shards"
done
[ -f "$out/samples.parquet" ] && [ -f "$out/summary.md" ] || fail "merge wrote no samples.parquet/summary.md"

"$RTW_SCAN" run "$config" --out "$work/single" --threads 2 >/dev/null 2>&1 ||
  fail "the single-machine run failed"
"$RTW_PY" scripts/compare_scans.py "$out/samples.parquet" "$work/single/samples.parquet" ||
  fail "the merged file differs from the single-machine run"
"$RTW_PY" scripts/compare_scans.py "$out/part-*.parquet" "$work/single/samples.parquet" ||
  fail "the parts, read with polars.scan_parquet, differ from the single-machine run"

# A lost shard rerun alone, as docs/cluster.md says (RTW_SHARDS: that array has
# one task), then merged again: still the single-machine rows.
rm "$out/part-2.parquet" "$out/samples.parquet"
jid=$(sbatch --parsable --array=2 --export=ALL,RTW_SHARDS=$shards --cpus-per-task=1 \
  --output="$work/rerun-%a.out" scripts/slurm/scan-array.sbatch "$config" "$out")
merge_state=$(submit_wait "$work/merge2.out" --dependency=afterok:"$jid" scripts/slurm/merge.sbatch "$out")
[ "$merge_state" = COMPLETED ] ||
  fail "the rerun of shard 2 or its merge failed ($merge_state): $(cat "$work"/rerun-2.out "$work"/merge2.out 2>/dev/null)"
grep -q "shard 2/$shards" "$work/rerun-2.out" || fail "the rerun did not run shard 2/$shards"
"$RTW_PY" scripts/compare_scans.py "$out/samples.parquet" "$work/single/samples.parquet" ||
  fail "after rerunning shard 2, the merged file differs from the single-machine run"

# A failing task (no such config) makes the merge's dependency impossible:
# Slurm cancels the merge instead of leaving it pending, and nothing is merged.
bad=$work/bad
jid=$(sbatch --parsable --array=0-1 --cpus-per-task=1 --output="$work/bad-%a.out" \
  scripts/slurm/scan-array.sbatch "$work/no-such-config.toml" "$bad")
merge_state=$(submit_wait "$work/merge-bad.out" --dependency=afterok:"$jid" scripts/slurm/merge.sbatch "$bad")
[ "$merge_state" = CANCELLED ] || fail "after a failed array the merge job ended $merge_state, not CANCELLED"
grep -q "cannot read config" "$work/bad-0.out" || fail "the failing task did not say why: $(cat "$work/bad-0.out")"
[ ! -e "$bad/samples.parquet" ] || fail "a samples.parquet was merged from a failed array"

echo "test_slurm: passed: $shards Slurm array tasks + merge give the single-machine rows, also after a shard is rerun alone; a failed array cancels the merge ($(($(date +%s) - started)) s)"
