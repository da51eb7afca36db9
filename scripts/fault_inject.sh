#!/usr/bin/env bash
# Fault injection, run by scripts/test.sh, so that no fault loses a finished
# result: a scan
# (configs/test/fault.toml, 400 samples, about a second on 2 cores) is
#   1. killed at random points, alternately with SIGKILL and SIGTERM, and
#      resumed, checking after each kill that no finished chunk was lost;
#   2. run on a full disk (a small tmpfs; needs root, else skipped with a
#      message), which must fail cleanly, then resumed once there is room;
#   3. corrupted: bytes flipped in a data page of the finished file, a part
#      and a finished chunk, which summary, merge and --resume must refuse or
#      redo;
#   4. killed (SIGKILL) at each step of a run's start and end: before its
#      manifest exists, during the final merge, after it, and while .partial
#      is being removed (the test build's RTW_SCAN_PAUSE stops the run there),
#      with a stray file of the user's in .partial; --resume must finish each
#      without computing a finished row again, and leave the stray file alone;
#   5. refine killed at random points: finished rounds never change, and the
#      same command finishes with the uninterrupted refine's rows;
#   6. continuation --through killed at random points: its four files appear
#      all together or not at all;
#   7. a bifurcation sweep, sensitivity and basin killed at random points,
#      over an earlier result of theirs: the earlier files stay byte for byte
#      or are replaced whole (the sweep's three together), and no temporary
#      file is left after a SIGTERM;
#   8. a design search killed at random points: each evaluation it stored is
#      the uninterrupted search's of that index, and the same command
#      finishes with its every row (search.parquet, designs.parquet); a slope
#      profile killed over an earlier profile of its own keeps it whole or
#      replaces it by the uninterrupted one (FAULT_ONLY=design runs this part
#      alone, in a few seconds);
# and every result is compared row by row (scripts/compare_scans.py) with an
# uninterrupted run. The random points come from a seed, printed (set
# FAULT_SEED to replay one). Exits non-zero if any finished row was lost or
# changed, or a fault was not handled as promised (docs/results-on-disk.md).
. "$(dirname "$0")/lib.sh"

seed=${FAULT_SEED:-$(( $(date +%s) % 32768 ))}
RANDOM=$seed
echo "fault_inject: seed $seed (FAULT_SEED=$seed ./scripts/fault_inject.sh replays it)"

# The command's test build (RTW_SCAN_PAUSE, part 4): the binary `cargo
# test` builds, over the same library as the plain build.
rtw_build -p rtw-scan-test
bin=$PWD/target/release/rtw-scan-test
rtw_venv >/dev/null
py=$RTW_PY
config=configs/test/fault.toml
work=$(mktemp -d)
mounted=""
cleanup() {
  [ -n "$mounted" ] && umount "$mounted" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

faults=0
fail() {
  echo "fault_inject: FAILED: $*" >&2
  exit 1
}
# Run options shared by every run: small chunks, so kills land between many.
scan=(run "$config" --threads 2 --chunk-size 8 --quiet)

# compare DIR WHAT: DIR/samples.parquet has exactly the reference rows.
compare() {
  "$py" scripts/compare_scans.py "$work/ref/samples.parquet" "$1/samples.parquet" >/dev/null ||
    fail "$2: the rows differ from the uninterrupted run's"
}

# Rows in the finished chunks of DIR/.partial.
finished_rows() {
  local n=0 f
  for f in "$1"/.partial/chunk-*.parquet; do
    [ -e "$f" ] && n=$((n + 8))
  done
  echo "$n"
}

# same_table A B: the two Parquet files hold equal tables (no timing column).
same_table() {
  "$py" - "$1" "$2" <<'PY' || return 1
import sys, pyarrow.parquet as pq
a, b = (pq.read_table(f).to_pandas() for f in sys.argv[1:3])
sys.exit(0 if a.equals(b) else 1)  # NaN where NaN (an index not estimable)
PY
}

# sleep_ms MS
sleep_ms() { sleep "$(printf '%d.%03d' $(($1 / 1000)) $(($1 % 1000)))"; }

if [ "${FAULT_ONLY:-}" != design ]; then
"$bin" "${scan[@]}" --out "$work/ref" >/dev/null || fail "the uninterrupted run failed"

# 1. Kills at random points, each followed by a resumed run that is killed in turn.
out=$work/killed
kept=0
for i in $(seq 8); do
  sig=KILL
  [ $((i % 2)) -eq 0 ] && sig=TERM
  delay_ms=$((20 + RANDOM % 400))
  "$bin" "${scan[@]}" --out "$out" --resume >/dev/null 2>&1 &
  pid=$!
  sleep "$(printf '0.%03d' "$delay_ms")"
  kill -s "$sig" "$pid" 2>/dev/null || true
  set +e
  wait "$pid" 2>/dev/null # (bash's "Killed" notice)
  code=$?
  set -e
  faults=$((faults + 1))
  # The merged file is written whole, before .partial's clean-up removes the
  # chunks one by one: a kill during that clean-up leaves fewer chunks but
  # loses no row (they are all in samples.parquet, which the final resume's
  # comparison checks, after it finishes the clean-up).
  if [ -f "$out/samples.parquet" ]; then
    echo "fault_inject: kill $i (SIG$sig after ${delay_ms} ms): the run had already merged its rows"
    break
  fi
  case $sig:$code in
    KILL:137 | TERM:130 | TERM:0 | KILL:0) ;;
    *) fail "kill $i: SIG$sig gave exit status $code" ;;
  esac
  now=$(finished_rows "$out")
  echo "fault_inject: kill $i (SIG$sig after ${delay_ms} ms, exit $code): $now rows in finished chunks"
  [ "$now" -ge "$kept" ] || fail "kill $i: finished chunks were lost ($kept rows before, $now after)"
  kept=$now
done
"$bin" "${scan[@]}" --out "$out" --resume >/dev/null || fail "the final resume failed"
compare "$out" "killed and resumed"
[ ! -d "$out/.partial" ] || fail "the final resume left $out/.partial"

# 2. A full disk: a tmpfs too small for the scan; the run must fail with an
# error (not an abort), keep what it finished, and resume once there is room.
if [ "$(id -u)" != 0 ]; then
  echo "fault_inject: full disk: skipped: needs root (to mount a small tmpfs)"
else
  disk=$work/disk
  mkdir -p "$disk"
  if mount -t tmpfs -o size=96k tmpfs "$disk" 2>/dev/null; then
    mounted=$disk
    set +e
    # --force: past the estimate at start (which refuses this scan on this
    # disk), so that the disk fills while the run writes.
    "$bin" "${scan[@]}" --out "$disk/scan" --force >"$work/full.out" 2>"$work/full.err"
    code=$?
    set -e
    faults=$((faults + 1))
    [ "$code" = 1 ] || fail "full disk: exit status $code, expected 1: $(cat "$work/full.err")"
    grep -q "^error: " "$work/full.err" || fail "full disk: no error message"
    echo "fault_inject: full disk: refused cleanly ($(head -c 120 "$work/full.err" | tr '\n' ' ')...); $(finished_rows "$disk/scan") rows kept"
    mount -o remount,size=64m "$disk" || fail "cannot grow the tmpfs"
    "$bin" "${scan[@]}" --out "$disk/scan" --resume >/dev/null || fail "full disk: the resume failed"
    compare "$disk/scan" "full disk, resumed"
  else
    echo "fault_inject: full disk: skipped: mounting a tmpfs is not permitted here"
  fi
fi

# flip FILE COLUMN: flips 40 bytes at a random point in the middle half of
# COLUMN's data in row group 0 (random doubles do not compress: zstd keeps
# them raw, so the page still decodes, to other numbers).
flip() {
  "$py" - "$1" "$2" "$RANDOM" <<'EOF'
import sys
import pyarrow.parquet as pq
path, column, r = sys.argv[1], sys.argv[2], int(sys.argv[3])
rg = pq.ParquetFile(path).metadata.row_group(0)
col = next(rg.column(i) for i in range(rg.num_columns) if rg.column(i).path_in_schema == column)
start = col.data_page_offset
size = col.total_compressed_size
at = start + size // 4 + r % max(1, size // 2 - 40)
data = bytearray(open(path, "rb").read())
for i in range(at, at + 40):
    data[i] ^= 0x5A
open(path, "wb").write(data)
EOF
}

# 3a. The finished file: summary and cluster refuse it, and write nothing.
bad=$work/corrupt
cp -r "$work/ref" "$bad"
for column in alpha fn phi; do
  cp "$work/ref/samples.parquet" "$bad/samples.parquet"
  flip "$bad/samples.parquet" "$column"
  faults=$((faults + 1))
  for cmd in summary cluster; do
    if "$bin" "$cmd" "$bad/samples.parquet" >/dev/null 2>"$work/corrupt.err"; then
      fail "corrupt $column page: $cmd accepted it"
    fi
    grep -q "corrupt" "$work/corrupt.err" || fail "corrupt $column page: $cmd did not say so: $(cat "$work/corrupt.err")"
  done
  cmp -s "$bad/summary.json" "$work/ref/summary.json" || fail "corrupt $column page: summary.json was rewritten"
  echo "fault_inject: corrupt $column page of samples.parquet: refused by summary and cluster"
done

# 3b. A part: merge refuses it; rerunning that shard repairs the scan.
parts=$work/parts
for k in 0 1; do "$bin" "${scan[@]}" --out "$parts" --shard "$k/2" >/dev/null; done
flip "$parts/part-1.parquet" rho
faults=$((faults + 1))
if "$bin" merge "$parts" --quiet >/dev/null 2>"$work/merge.err"; then fail "merge accepted a corrupt part"; fi
grep "part-1.parquet" "$work/merge.err" | grep -q "corrupt" || fail "merge did not name the corrupt part: $(cat "$work/merge.err")"
[ ! -e "$parts/samples.parquet" ] || fail "merge wrote a samples.parquet from a corrupt part"
rm "$parts/part-1.parquet"
"$bin" "${scan[@]}" --out "$parts" --shard 1/2 >/dev/null
"$bin" merge "$parts" --quiet >/dev/null || fail "merge after rerunning the corrupt shard failed"
compare "$parts" "corrupt part, shard rerun"
echo "fault_inject: corrupt page of part-1.parquet: refused by merge; the shard rerun merges to the reference rows"

# 3c. A finished chunk of an interrupted run: --resume redoes it.
chunked=$work/chunked
"$bin" "${scan[@]}" --out "$chunked" >/dev/null 2>&1 &
pid=$!
while [ ! -e "$chunked/.partial/chunk-00003.parquet" ]; do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.01
done
kill -KILL "$pid" 2>/dev/null || true
wait "$pid" 2>/dev/null || true
if [ -e "$chunked/.partial/chunk-00002.parquet" ]; then
  flip "$chunked/.partial/chunk-00002.parquet" alpha
  faults=$((faults + 1))
  "$bin" run "$config" --threads 2 --out "$chunked" --resume 2>"$work/resume.err" >/dev/null ||
    fail "the resume after a corrupt chunk failed: $(cat "$work/resume.err")"
  grep -q "redoing .*chunk-00002.parquet" "$work/resume.err" || fail "the corrupt chunk was not redone: $(cat "$work/resume.err")"
  compare "$chunked" "corrupt chunk, resumed"
  echo "fault_inject: corrupt finished chunk: redone by --resume"
else
  echo "fault_inject: corrupt chunk: the run finished before it could be killed; not injected"
fi

# 4. SIGKILL at the steps of a run's start and end, each resumed.
for point in manifest merge merged cleanup; do
  out=$work/end-$point
  RTW_SCAN_PAUSE=$point "$bin" "${scan[@]}" --out "$out" >/dev/null 2>"$work/pause.err" &
  pid=$!
  for _ in $(seq 6000); do
    grep -q "paused at $point" "$work/pause.err" && break
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.01
  done
  grep -q "paused at $point" "$work/pause.err" || fail "the run did not pause at $point: $(cat "$work/pause.err")"
  kill -KILL "$pid"
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  [ -d "$out/.partial" ] || fail "killed at $point: no .partial left to resume"
  kept=$(finished_rows "$out")
  [ -f "$out/samples.parquet" ] && kept="all 400 (samples.parquet)"
  echo "note" >"$out/.partial/notes.txt"
  "$bin" run "$config" --threads 2 --out "$out" --resume >/dev/null 2>"$work/resume.err" ||
    fail "the resume after a kill at $point failed: $(cat "$work/resume.err")"
  if [ "$point" != manifest ]; then
    grep -q "already complete" "$work/resume.err" ||
      fail "killed at $point: the resume computed finished rows again: $(cat "$work/resume.err")"
  fi
  grep -q "notes.txt" "$work/resume.err" || fail "killed at $point: the stray notes.txt was not reported"
  [ "$(cat "$out/.partial/notes.txt")" = note ] || fail "killed at $point: the stray notes.txt was touched"
  compare "$out" "killed at $point, resumed"
  echo "fault_inject: SIGKILL at $point: $kept rows finished; resumed to the reference rows, the stray file kept"
done

# 5. refine killed at random instants (SIGKILL and SIGTERM alternately), each
# followed by the same command: a finished round is never changed, the
# combined file appears only whole, and the end has the uninterrupted rows.
refine_args=(--budget 48 --rounds 3 --seed 5 --threads 2 --quiet)
cp -r "$work/ref" "$work/refine-ref"
"$bin" refine "$work/refine-ref" "${refine_args[@]}" >/dev/null || fail "the uninterrupted refine failed"
cp -r "$work/ref" "$work/refine-killed"
for i in 1 2 3 4; do
  sig=KILL
  [ $((i % 2)) -eq 0 ] && sig=TERM
  delay_ms=$((20 + RANDOM % 300))
  declare -A before=()
  for f in "$work"/refine-killed/refine/round-*/samples.parquet; do
    [ -e "$f" ] && before[$f]=$(cksum <"$f")
  done
  "$bin" refine "$work/refine-killed" "${refine_args[@]}" >/dev/null 2>&1 &
  pid=$!
  sleep "$(printf '0.%03d' "$delay_ms")"
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  for f in "${!before[@]}"; do
    [ "$(cksum <"$f")" = "${before[$f]}" ] || fail "refine kill $i: the finished round $f changed"
  done
  unset before
  if [ -e "$work/refine-killed/refine/samples.parquet" ]; then
    "$py" scripts/compare_scans.py "$work/refine-ref/refine/samples.parquet" \
      "$work/refine-killed/refine/samples.parquet" >/dev/null ||
      fail "refine kill $i: the combined file differs from the uninterrupted refine's"
  fi
  echo "fault_inject: refine kill $i (SIG$sig after ${delay_ms} ms): finished rounds kept"
done
"$bin" refine "$work/refine-killed" "${refine_args[@]}" >/dev/null || fail "the final refine failed"
"$py" scripts/compare_scans.py "$work/refine-ref/refine/samples.parquet" \
  "$work/refine-killed/refine/samples.parquet" >/dev/null ||
  fail "refine killed and resumed: the rows differ from the uninterrupted refine's"

# 6. continuation --through killed at random instants: its files (branch
# points, special points, segments, summary) appear all together or none.
cont_args=(continuation --phi 0.094 --set strings.rest_length_ratio=0.85 --from 0.0925 --to 0.0955 --through 1)
set_of() {
  local n=0 f
  for f in d.parquet d.special.parquet d.segments.json d.md; do
    [ -e "$1/$f" ] && n=$((n + 1))
  done
  echo "$n"
}
for i in 1 2 3; do
  cdir=$work/cont-$i
  mkdir -p "$cdir"
  sig=TERM
  [ $((i % 2)) -eq 0 ] && sig=KILL
  delay_ms=$((50 + RANDOM % 1500))
  "$bin" "${cont_args[@]}" --out "$cdir/d.parquet" >/dev/null 2>&1 &
  pid=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  n=$(set_of "$cdir")
  [ "$n" = 0 ] || [ "$n" = 4 ] || fail "continuation kill $i (SIG$sig): $n of its 4 files left"
  if [ "$sig" = TERM ] && ls -A "$cdir" | grep -q '\.tmp$'; then
    fail "continuation kill $i (SIGTERM): temporary files left: $(ls -A "$cdir")"
  fi
  # The next run removes what a SIGKILL left and writes the whole set.
  "$bin" "${cont_args[@]}" --out "$cdir/d.parquet" >/dev/null || fail "continuation after kill $i failed"
  [ "$(set_of "$cdir")" = 4 ] || fail "continuation after kill $i: not every file written"
  ! ls -A "$cdir" | grep -q '\.tmp$' || fail "continuation after kill $i: temporary files left"
  echo "fault_inject: continuation --through kill $i (SIG$sig after ${delay_ms} ms): $n of 4 files, never a part of the set"
done

# 7. sensitivity and basin killed at random instants, each over an earlier
# result of its own at --out: that file is never lost, never left part
# written, and either kept byte for byte or replaced by the whole new result
# (the same rows as an uninterrupted run's).
kill_study() { # WHAT OUT ARGS...: kills `rtw-scan ARGS` four times over OUT
  local what=$1 out=$2 i sig delay_ms before
  shift 2
  "$bin" "$@" --out "$work/$what-ref.parquet" >/dev/null 2>&1 || fail "the uninterrupted $what failed"
  cp "$work/$what-ref.parquet" "$out"
  for i in 1 2 3 4; do
    sig=KILL
    [ $((i % 2)) -eq 0 ] && sig=TERM
    delay_ms=$((50 + RANDOM % 1500))
    before=$(cksum <"$out")
    "$bin" "$@" --out "$out" >/dev/null 2>&1 &
    pid=$!
    sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
    kill -s "$sig" "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    faults=$((faults + 1))
    [ -f "$out" ] || fail "$what kill $i (SIG$sig): its earlier result $out is gone"
    if [ "$(cksum <"$out")" != "$before" ]; then
      same_table "$work/$what-ref.parquet" "$out" ||
        fail "$what kill $i (SIG$sig): $out changed, and not to the whole result"
    fi
    if [ "$sig" = TERM ] && ls -A "$(dirname "$out")" | grep -q '\.tmp$'; then
      fail "$what kill $i (SIGTERM): temporary files left: $(ls -A "$(dirname "$out")")"
    fi
    echo "fault_inject: $what kill $i (SIG$sig after ${delay_ms} ms): the earlier result kept whole"
  done
  # The next run removes what a SIGKILL left and writes the whole result.
  "$bin" "$@" --out "$out" >/dev/null 2>&1 || fail "$what after the kills failed"
  same_table "$work/$what-ref.parquet" "$out" || fail "$what after the kills: other rows"
  ! ls -A "$(dirname "$out")" | grep -q '\.tmp$' || fail "$what after the kills: temporary files left"
}
# A bifurcation sweep killed at random instants over an earlier sweep of
# its own: its three files (the values, the steps, the summary) are one set,
# kept as they were or replaced together, never a mix of two sweeps.
sweep_args=(bifurcation --from 0.14 --to 0.16 --points 6 --transient 40 --record 4)
sdir=$work/sweep
mkdir -p "$sdir"
"$bin" "${sweep_args[@]}" --out "$sdir/s.parquet" >/dev/null 2>&1 || fail "the uninterrupted sweep failed"
for i in 1 2 3 4; do
  sig=KILL
  [ $((i % 2)) -eq 0 ] && sig=TERM
  delay_ms=$((50 + RANDOM % 1500))
  before=$(for f in s.parquet s.steps.parquet s.md; do cksum <"$sdir/$f"; done)
  "$bin" "${sweep_args[@]}" --out "$sdir/s.parquet" >/dev/null 2>&1 &
  pid=$!
  sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  changed=0
  k=0
  for f in s.parquet s.steps.parquet s.md; do
    k=$((k + 1))
    [ -f "$sdir/$f" ] || fail "sweep kill $i (SIG$sig): $f is gone"
    [ "$(cksum <"$sdir/$f")" = "$(sed -n "${k}p" <<<"$before")" ] || changed=$((changed + 1))
  done
  [ "$changed" = 0 ] || [ "$changed" = 3 ] || fail "sweep kill $i (SIG$sig): $changed of its 3 files replaced"
  if [ "$sig" = TERM ] && ls -A "$sdir" | grep -q '\.tmp$'; then
    fail "sweep kill $i (SIG$sig): temporary files left: $(ls -A "$sdir")"
  fi
  echo "fault_inject: bifurcation kill $i (SIG$sig after ${delay_ms} ms): $changed of 3 files replaced, never a part of the set"
done

mkdir -p "$work/studies"
kill_study sensitivity "$work/ref/indices.parquet" sensitivity "$work/ref" --resamples 2000
kill_study basin "$work/studies/basin.parquet" basin --x omega_a:-40:40:9 --y theta_b:-1.2:0.8:9 --steps 60 --threads 2
fi

# 8. A design search killed at random instants (SIGKILL and SIGTERM
# alternately), each followed by the same command, killed in turn: each
# evaluation it stored is the uninterrupted search's of that index, and the
# last run ends with its every row. A tiny search (the paper's box, slopes
# [0.05, 0.3] on a 0.05 grid: about a second).
design=$work/design.toml
cat >"$design" <<'TOML'
name = "fault"
seed = 3
budget = 300
batch = 4
report = 2
objectives = ["slope_range"]
[box]
rho = [1.0, 5.0]
alpha = [0.0, 0.4]
fn = [1.5, 5.0]
zeta = [0.05, 0.1]
[slopes]
from = 0.05
to = 0.3
grid = 0.05
tol = 0.01
verify_grid = 0.025
TOML
"$bin" design "$design" --out "$work/design-ref" --threads 2 --quiet >/dev/null ||
  fail "the uninterrupted design search failed"
# kept_of REF PART: each of PART's rows is REF's row of the same index (a
# search stopped inside a generation keeps the designs that finished).
kept_of() {
  "$py" - "$1" "$2" <<'PY' || return 1
import sys, pyarrow.parquet as pq
ref, part = (pq.read_table(f).to_pandas() for f in sys.argv[1:3])
ok = part["index"].is_unique and part["index"].isin(ref["index"]).all()
if ok:
    mine = ref.set_index("index").loc[part["index"]].reset_index()
    ok = mine[list(part.columns)].equals(part)
sys.exit(0 if ok else 1)
PY
}
rows_of() { "$py" -c "import sys, pyarrow.parquet as pq; print(pq.read_metadata(sys.argv[1]).num_rows)" "$1"; }
out=$work/design-killed
for i in 1 2 3 4; do
  sig=KILL
  [ $((i % 2)) -eq 0 ] && sig=TERM
  delay_ms=$((100 + RANDOM % 1500))
  "$bin" design "$design" --out "$out" --threads 2 --quiet >/dev/null 2>&1 &
  pid=$!
  sleep_ms "$delay_ms"
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  n=0
  # What a kill keeps: search.parquet (merged at an earlier stop) and the
  # parts the search appended after each generation since.
  for f in "$out/search.parquet" "$out"/search.part-*.parquet; do
    [ -e "$f" ] || continue
    kept_of "$work/design-ref/search.parquet" "$f" ||
      fail "design kill $i (SIG$sig): a stored evaluation in $(basename "$f") is not the uninterrupted search's"
    n=$((n + $(rows_of "$f")))
  done
  if [ "$sig" = TERM ] && ls -A "$out" 2>/dev/null | grep -qE '\.tmp$|^search\.part-'; then
    fail "design kill $i (SIGTERM): temporary files or unmerged parts left: $(ls -A "$out")"
  fi
  echo "fault_inject: design kill $i (SIG$sig after ${delay_ms} ms): $n evaluations kept, each the uninterrupted search's"
done
"$bin" design "$design" --out "$out" --threads 2 --quiet >/dev/null || fail "the design search after the kills failed"
for f in search.parquet designs.parquet; do
  same_table "$work/design-ref/$f" "$out/$f" ||
    fail "design search killed and resumed: $f differs from the uninterrupted search's"
done
! ls -A "$out" | grep -qE '\.tmp$|^search\.part-' || fail "design search after the kills: temporary files or parts left"

# A slope profile killed at random instants over an earlier profile of its
# own at --out: that file is kept byte for byte, or replaced by the whole
# uninterrupted profile (its rows, timing aside, and its profile's JSON; a
# profile has no scan config, which compare_scans.py requires).
same_profile() {
  "$py" - "$1" "$2" <<'PY' || return 1
import sys, pyarrow.parquet as pq
a, b = (pq.read_table(f) for f in sys.argv[1:3])
key = b"rtw.profile"
same_json = len({pq.read_metadata(f).metadata[key] for f in sys.argv[1:3]}) == 1
rows = [t.drop_columns(["wall_time_s"]).to_pandas() for t in (a, b)]
sys.exit(0 if same_json and rows[0].equals(rows[1]) else 1)
PY
}
profile=(profile --length 0.8 --rho 2.5 --alpha 0.125 --fn 3.269 --zeta 0.0514 --from 0.05 --to 0.3
  --grid 2e-4 --tol 1e-4 --threads 2 --quiet)
"$bin" "${profile[@]}" --out "$work/profile-ref.parquet" >/dev/null || fail "the uninterrupted profile failed"
mkdir -p "$work/profile"
out=$work/profile/p.parquet
cp "$work/profile-ref.parquet" "$out"
for i in 1 2 3 4; do
  sig=KILL
  [ $((i % 2)) -eq 0 ] && sig=TERM
  delay_ms=$((50 + RANDOM % 900))
  before=$(cksum <"$out")
  "$bin" "${profile[@]}" --out "$out" >/dev/null 2>&1 &
  pid=$!
  sleep_ms "$delay_ms"
  kill -s "$sig" "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  faults=$((faults + 1))
  [ -f "$out" ] || fail "profile kill $i (SIG$sig): its earlier result is gone"
  if [ "$(cksum <"$out")" != "$before" ]; then
    same_profile "$work/profile-ref.parquet" "$out" ||
      fail "profile kill $i (SIG$sig): $out changed, and not to the whole profile"
  fi
  if [ "$sig" = TERM ] && ls -A "$work/profile" | grep -q '\.tmp$'; then
    fail "profile kill $i (SIGTERM): temporary files left: $(ls -A "$work/profile")"
  fi
  echo "fault_inject: profile kill $i (SIG$sig after ${delay_ms} ms): the earlier profile kept whole"
done
rm "$out"
"$bin" "${profile[@]}" --out "$out" >/dev/null || fail "the profile after the kills failed"
same_profile "$work/profile-ref.parquet" "$out" ||
  fail "profile after the kills: other rows than the uninterrupted profile's"

echo "fault_inject: passed: $faults faults injected (seed $seed); no finished row was lost or changed"
