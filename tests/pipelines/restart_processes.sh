#!/usr/bin/env bash
# restart_processes.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE [INTERVAL] [--set=KEY=VALUE]...
# The smoke scene of pipelines/CASE run over 2 MPI processes with checkpoints every INTERVAL
# seconds (default 0.1; WORK/np2, through the pipeline, so a coupled case has its mesh, modes
# and mapped modes there), then continued from its first checkpoint (a copy of the folder each)
# as one process (WORK/restart_np1) and over 3 processes (WORK/restart_np3): each
# continuation's probes within 10× the PPE tolerance of the uninterrupted 2-process run
# (check_processes.py). --set=KEY=VALUE: a scene setting for every run. As root (CI) OpenMPI
# needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1, set here; 3 processes oversubscribe 2 cores.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"; shift 4
interval=0.1
if [ $# -gt 0 ] && [[ "$1" != --* ]]; then interval="$1"; shift; fi
settings=("time.checkpoint_interval=$interval")
for option in "$@"; do
  case "$option" in
    --set=*) settings+=("${option#--set=}") ;;
    *) echo "restart_processes.sh: unknown option $option" >&2; exit 2 ;;
  esac
done
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
simulate="$build_dir/stages/fsi-simulate/fsi-simulate"
scene="$source_dir/pipelines/$case_name/scene.smoke.toml"
rm -rf "$work"
make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" OUT="$work/np2" \
  NP=2 MPIRUN="mpirun --oversubscribe" SET="${settings[*]}" simulate
first=$(ls "$work/np2/checkpoints" | sort | head -1)
test -n "$first"
echo "continuing from checkpoints/$first"
for np in 1 3; do
  folder="$work/restart_np$np"
  cp -r "$work/np2" "$folder"
  arguments=("$scene")
  for setting in "${settings[@]}"; do arguments+=(--set "$setting"); done
  for input in mesh modes mapped; do  # the inputs the pipeline gave the uninterrupted run
    if [ -f "$folder/$input.h5" ]; then arguments+=("--$input" "$folder/$input.h5"); fi
  done
  launch=()
  if [ "$np" != 1 ]; then launch=(mpirun --oversubscribe -np "$np"); fi
  "${launch[@]}" "$simulate" "${arguments[@]}" --restart "$folder/checkpoints/$first" \
    -o "$folder/results.h5" -q
  python3 "$source_dir/tests/pipelines/check_processes.py" "$work/np2" "$folder" "$scene"
done
