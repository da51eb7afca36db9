#!/usr/bin/env bash
# Scaling of a sharded scan on the one-node local Slurm cluster
# (scripts/slurm/local-cluster.sh), against a plain run on the same machine.
#
#   scripts/slurm/bench.sh [CONFIG] [REPEATS]     (default configs/paper.toml, 3)
#
# Modes, each run REPEATS times (medians reported):
#   plain         rtw-scan run CONFIG --threads <nproc>, no Slurm
#   slurm 1x<c>   a 1-task array with --cpus-per-task=<nproc>, + merge job
#   slurm 4x1     a 4-task array with --cpus-per-task=1 (<nproc> at once), + merge
#   slurm 4x<c>   a 4-task array with --cpus-per-task=<nproc> (one at a time), + merge
# "elapsed" runs from the first sbatch to the end of the merge job (polled every
# 0.1 s), so it includes Slurm's scheduling, the merge and the summary; "per task"
# is a task's rows over its own compute time (the part's rtw.wall_time_s).
# Prints a Markdown table.
. "$(dirname "$0")/../lib.sh"
config=${1:-configs/paper.toml}
repeats=${2:-3}
cpus=$(nproc)

rtw_build
export RTW_SCAN=$(cd "$(dirname "$RTW_BIN")" && pwd)/rtw-scan
rtw_venv

work=$(mktemp -d)
state=$work/slurm
trap 'scripts/slurm/local-cluster.sh stop "$state" >/dev/null || true; rm -rf "$work"' EXIT
scripts/slurm/local-cluster.sh start "$state" >&2
export SLURM_CONF=$state/slurm.conf

now() { date +%s.%N; }

# Median of the numbers on stdin.
median() { sort -g | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

# rows/wall_time_s of each part in DIR, one a line.
task_rates() {
  .venv/bin/python - "$1" <<'EOF'
import glob, sys
import pyarrow.parquet as pq
for p in sorted(glob.glob(sys.argv[1] + "/part-*.parquet")):
    md = pq.read_metadata(p)
    print(md.num_rows / float(md.metadata[b"rtw.wall_time_s"]))
EOF
}

rows=$("$RTW_SCAN" run "$config" --out "$work/rows" --threads "$cpus" 2>/dev/null | sed -n 's/^- samples: \([0-9]*\).*/\1/p')

# slurm_run TASKS CPUS_PER_TASK OUT: prints elapsed seconds.
slurm_run() {
  local n=$1 c=$2 out=$3 t0 jid mid
  t0=$(now)
  jid=$(sbatch --parsable --array=0-$((n - 1)) --cpus-per-task="$c" --output=/dev/null \
    scripts/slurm/scan-array.sbatch "$config" "$out")
  mid=$(sbatch --parsable --dependency=afterok:"$jid" --output=/dev/null scripts/slurm/merge.sbatch "$out")
  while [ -n "$(squeue -h -j "$jid,$mid" 2>/dev/null)" ]; do sleep 0.1; done
  scontrol show job "$mid" | grep -q 'JobState=COMPLETED' || {
    echo "bench: the merge job $mid did not complete" >&2
    exit 1
  }
  echo "$(now) - $t0" | bc -l
}

declare -A elapsed task
modes=("plain" "slurm 1x$cpus" "slurm 4x1" "slurm 4x$cpus")
for r in $(seq "$repeats"); do
  for m in "${modes[@]}"; do
    out=$work/run-$r-${m// /-}
    case $m in
      plain)
        t0=$(now)
        "$RTW_SCAN" run "$config" --out "$out" --threads "$cpus" >/dev/null 2>&1
        e=$(echo "$(now) - $t0" | bc -l)
        ;;
      *)
        spec=${m#slurm }
        e=$(slurm_run "${spec%x*}" "${spec#*x}" "$out")
        task[$m]+="$(task_rates "$out" | tr '\n' ' ')"
        ;;
    esac
    elapsed[$m]+="$e "
    echo "bench: repeat $r, $m: $e s" >&2
  done
done

echo "| mode | tasks × CPUs | median elapsed (s) | samples/s | vs plain | median per-task samples/s |"
echo "|---|---|---:|---:|---:|---:|"
plain=$(echo "${elapsed[plain]}" | tr ' ' '\n' | grep . | median)
for m in "${modes[@]}"; do
  e=$(echo "${elapsed[$m]}" | tr ' ' '\n' | grep . | median)
  rate=$(echo "$rows / $e" | bc -l)
  ratio=$(echo "$plain / $e" | bc -l)
  if [ "$m" = plain ]; then
    shape="1 × $cpus threads"
    pt="–"
  else
    spec=${m#slurm }
    shape="${spec%x*} × ${spec#*x}"
    pt=$(printf '%.0f' "$(echo "${task[$m]}" | tr ' ' '\n' | grep . | median)")
  fi
  printf '| %s | %s | %.2f | %.0f | %.2f | %s |\n' "$m" "$shape" "$e" "$rate" "$ratio" "$pt"
done
echo
echo "$rows samples of $config, $repeats repeats, $(nproc) cores; scripts/slurm/bench.sh $*"
