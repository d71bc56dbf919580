#!/usr/bin/env bash
# restart_processes.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE
# The smoke scene of pipelines/CASE run over 2 MPI processes with checkpoints every 0.1 s
# (WORK/np2), then continued from its first checkpoint (a copy of the folder each) as one process
# (WORK/restart_np1) and over 3 processes (WORK/restart_np3): each continuation's probes within
# 10× the PPE tolerance of the uninterrupted 2-process run (check_processes.py). As root (CI)
# OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1, set here; 3 processes oversubscribe 2 cores.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
simulate="$build_dir/stages/fsi-simulate/fsi-simulate"
scene="$source_dir/pipelines/$case_name/scene.smoke.toml"
set_interval=(--set time.checkpoint_interval=0.1)
rm -rf "$work"; mkdir -p "$work/np2"
mpirun --oversubscribe -np 2 "$simulate" "$scene" "${set_interval[@]}" -o "$work/np2/results.h5" -q
first=$(ls "$work/np2/checkpoints" | sort | head -1)
test -n "$first"
echo "continuing from checkpoints/$first"
for np in 1 3; do
  cp -r "$work/np2" "$work/restart_np$np"
  launch=()
  if [ "$np" != 1 ]; then launch=(mpirun --oversubscribe -np "$np"); fi
  "${launch[@]}" "$simulate" "$scene" "${set_interval[@]}" \
    --restart "$work/restart_np$np/checkpoints/$first" -o "$work/restart_np$np/results.h5" -q
  python3 "$source_dir/tests/pipelines/check_processes.py" "$work/np2" "$work/restart_np$np" "$scene"
done
