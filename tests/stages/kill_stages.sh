#!/usr/bin/env bash
# kill_stages.sh STAGES_DIR SOURCE_DIR WORK
# kill -9 of every stage mid-run (fsi-mesh, fsi-modes, fsi-map on the elastic gate; fsi-simulate
# with snapshots and checkpoints; fsi-report), each at several moments: the output path then holds
# nothing or a complete artefact (fsi-inspect reads it), never a partial one. For fsi-simulate,
# killed once a checkpoint exists: every checkpoint left is readable, and the restart from the
# last one gives the uninterrupted run's probes.csv byte for byte and results.h5 to the last bit
# (all datasets but the wall-clock timings).
set -euo pipefail
stages="$1"; source_dir="$2"; work="$3"
gate="$source_dir/pipelines/elastic_gate/scene.toml"
hydro="$source_dir/tests/stages/data/hydrostatic_small.toml"
inspect="$stages/fsi-inspect/fsi-inspect"
export OMP_NUM_THREADS=1
rm -rf "$work"; mkdir -p "$work"

# Nothing, or a complete artefact, at OUTPUT.
check_output() {
  local output="$1" what="$2"
  if [ -e "$output" ]; then
    "$inspect" "$output" > /dev/null || { echo "kill: $what left a partial $output" >&2; exit 1; }
    echo "kill: $what: complete artefact at the output path (the stage had finished)"
  else
    echo "kill: $what: nothing at the output path"
  fi
}

# kill_at SECONDS OUTPUT COMMAND...: starts COMMAND, kills it with SIGKILL after SECONDS.
kill_at() {
  local delay="$1" output="$2"; shift 2
  rm -f "$output"
  "$@" -o "$output" -q > /dev/null 2>&1 &
  local pid=$!
  sleep "$delay"
  kill -9 "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  check_output "$output" "$(basename "$1") killed after $delay s"
}

# The inputs each stage reads, made once, uninterrupted. The gate is meshed at 0.3 mm so that
# every kill lands mid-run (on 2 cores, unloaded: fsi-mesh 0.54 s, fsi-modes 1.2 s, fsi-map
# 0.32 s).
fine=(--set structure.mesh.size=0.0003)
"$stages/fsi-mesh/fsi-mesh" "$gate" "${fine[@]}" -o "$work/mesh.h5" -q
"$stages/fsi-modes/fsi-modes" "$gate" "${fine[@]}" --mesh "$work/mesh.h5" -o "$work/modes.h5" -q
for delay in 0.05 0.2 0.4; do
  kill_at "$delay" "$work/k/mesh.h5" "$stages/fsi-mesh/fsi-mesh" "$gate" "${fine[@]}"
  kill_at "$delay" "$work/k/modes.h5" "$stages/fsi-modes/fsi-modes" "$gate" "${fine[@]}" \
    --mesh "$work/mesh.h5"
  kill_at "$delay" "$work/k/mapped.h5" "$stages/fsi-map/fsi-map" "$gate" "${fine[@]}" \
    --modes "$work/modes.h5"
done

# fsi-simulate: the small tank to 0.3 s, snapshots every 0.025 s, checkpoints every 0.02 s (killed
# at 0.04 s of the 0.3 s, however loaded the machine).
scene="$work/tank.toml"
sed -e 's/^end = 0.05$/end = 0.3/' \
    -e 's/^probe_interval = 0.01$/probe_interval = 0.01\ncheckpoint_interval = 0.02/' "$hydro" > "$scene"
mkdir -p "$work/A"
"$stages/fsi-simulate/fsi-simulate" "$scene" -o "$work/A/results.h5" -q
mkdir -p "$work/K"
"$stages/fsi-simulate/fsi-simulate" "$scene" -o "$work/K/results.h5" -q > /dev/null 2>&1 &
pid=$!
# Killed once two checkpoints exist (the second one may be being written).
until [ "$(ls "$work/K/checkpoints" 2> /dev/null | grep -c '\.h5$')" -ge 2 ] || ! kill -0 "$pid" 2> /dev/null; do
  sleep 0.02
done
kill -9 "$pid" 2> /dev/null || { echo "kill: fsi-simulate ended before the kill" >&2; exit 1; }
wait "$pid" 2> /dev/null || true
check_output "$work/K/results.h5" "fsi-simulate killed after its second checkpoint"
last=""
for checkpoint in $(ls "$work/K/checkpoints" | grep '\.h5$' | sort); do
  "$inspect" "$work/K/checkpoints/$checkpoint" > /dev/null
  last="$checkpoint"
done
echo "kill: every checkpoint left is readable; restarting from $last"
"$stages/fsi-simulate/fsi-simulate" "$scene" --restart "$work/K/checkpoints/$last" \
  -o "$work/K/results.h5" -q
cmp "$work/A/probes.csv" "$work/K/probes.csv"
for dataset in $(h5ls -r "$work/A/results.h5" | awk '$2 == "Dataset" {print $1}' |
                 grep -v -e seconds -e phase); do
  h5diff -d 0 "$work/A/results.h5" "$work/K/results.h5" "$dataset" "$dataset" ||
    { echo "kill: after the restart $dataset differs" >&2; exit 1; }
done
echo "kill: the restart after kill -9 reproduces the uninterrupted run bit for bit"

# fsi-report on the finished run.
for delay in 0.05 0.3; do
  kill_at "$delay" "$work/R/metrics.h5" "$stages/fsi-report/fsi-report" "$scene" --results "$work/A/results.h5"
done
echo "kill: every stage killed mid-run left nothing partial at its output path"
