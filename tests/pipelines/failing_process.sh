#!/usr/bin/env bash
# failing_process.sh SOURCE_DIR BUILD_DIR WORK_DIR
# fsi-simulate over 2 MPI processes when one of them fails, each case under a timeout (a hang
# fails the test) on the Koshizuka dam break's smoke scene:
#  1. process 0 alone fails (its snapshots folder cannot be made: a file is in the way) while
#     process 1 goes on into the run's collective calls: every process ends within the timeout
#     with process 0's exit code (2, invalid input) and message naming the path; nothing at the
#     output path;
#  2. process 1 is killed (SIGKILL) once the run has written a checkpoint: mpirun ends within the
#     timeout with a non-zero exit, nothing (or a complete artefact) at the output path, every
#     checkpoint left readable, and the run restarted from the last one over 2 processes
#     completes.
# As root (CI) OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1, set here.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
simulate="$build_dir/stages/fsi-simulate/fsi-simulate"
inspect="$build_dir/stages/fsi-inspect/fsi-inspect"
scene="$source_dir/pipelines/dambreak_koshizuka/scene.smoke.toml"
limit=60  # [s]: the smoke run takes about 2 s over 2 processes
rm -rf "$work"; mkdir -p "$work/one" "$work/killed"

# 1. Process 0 cannot make its snapshot folder.
touch "$work/one/snapshots"
status=0
timeout "$limit" mpirun --oversubscribe -np 2 "$simulate" "$scene" -o "$work/one/results.h5" -q \
  > "$work/one/log" 2>&1 || status=$?
cat "$work/one/log"
if [ "$status" = 124 ]; then echo "failing process: the run hung (timeout $limit s)" >&2; exit 1; fi
[ "$status" = 2 ] || { echo "failing process: exit $status, expected 2 (invalid input)" >&2; exit 1; }
grep -q "cannot create the snapshot folder '$work/one/snapshots'" "$work/one/log" ||
  { echo "failing process: the message does not name the snapshot folder" >&2; exit 1; }
[ ! -e "$work/one/results.h5" ] || { echo "failing process: results.h5 left behind" >&2; exit 1; }
echo "failing process: process 0's failure ended both processes (exit 2) and left no results.h5"

# 2. Process 1 killed mid-run, once a checkpoint is written.
settings=(--set time.end=0.5 --set time.checkpoint_interval=0.05)
timeout "$limit" mpirun --oversubscribe -np 2 "$simulate" "$scene" "${settings[@]}" \
  -o "$work/killed/results.h5" -q > "$work/killed/log" 2>&1 &
launcher=$!
until ls "$work/killed/checkpoints" 2> /dev/null | grep -q '\.h5$' || ! kill -0 "$launcher" 2> /dev/null; do
  sleep 0.05
done
victim=""
for pid in $(pgrep -f "fsi-simulate/fsi-simulate $scene" || true); do
  if tr '\0' '\n' < "/proc/$pid/environ" 2> /dev/null | grep -qx 'OMPI_COMM_WORLD_RANK=1'; then
    victim="$pid"
  fi
done
[ -n "$victim" ] || { echo "failing process: no process 1 to kill (did the run end early?)" >&2; exit 1; }
kill -9 "$victim"
status=0
wait "$launcher" || status=$?
cat "$work/killed/log"
if [ "$status" = 124 ]; then echo "failing process: the run hung after the kill" >&2; exit 1; fi
[ "$status" != 0 ] || { echo "failing process: exit 0 after a process was killed" >&2; exit 1; }
if [ -e "$work/killed/results.h5" ]; then "$inspect" "$work/killed/results.h5" > /dev/null; fi
last=""
for checkpoint in $(ls "$work/killed/checkpoints" | grep '\.h5$' | sort); do
  "$inspect" "$work/killed/checkpoints/$checkpoint" > /dev/null
  last="$checkpoint"
done
echo "failing process: killing process 1 ended the run (exit $status); every checkpoint readable"
timeout "$limit" mpirun --oversubscribe -np 2 "$simulate" "$scene" "${settings[@]}" \
  --restart "$work/killed/checkpoints/$last" -o "$work/killed/results.h5" -q
"$inspect" "$work/killed/results.h5" > /dev/null
echo "failing process: the restart from $last over 2 processes completed"
