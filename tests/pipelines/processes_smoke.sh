#!/usr/bin/env bash
# processes_smoke.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE NP [--twice] [--scatter]
#                    [--set=KEY=VALUE]... [--until-impact]
# The smoke variant of the flow pipeline pipelines/CASE run as one process (NP=1) and over NP
# MPI processes (make NP=NP: mpirun -np NP fsi-simulate), each into its own scratch folder;
# check_processes.py then holds every probe of the NP run to the one-process run within 10× the
# PPE tolerance of the probe's largest value (with --until-impact: up to the impact, after which
# a violent flow is chaotic; the time the runs part is printed), and the NP run to have
# completed. With --twice the NP run is made again and must equal the first bit for bit
# (probes.csv and every results.h5 dataset but the wall-clock timings). --set=KEY=VALUE: a scene
# setting for every run (e.g. the one process on the PPE solver the processes use). --scatter:
# the one process also at a 10× tighter PPE tolerance, and each probe held to the larger of 10×
# the tolerance and twice the one process's own distance from that run (check_processes.py). Run as root (CI), OpenMPI
# needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1, set here; --oversubscribe lets NP exceed the cores.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"; processes="$5"; shift 5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work"; mkdir -p "$work"
twice=false
scatter=false
settings=()
check_options=()
for option in "$@"; do
  case "$option" in
    --twice) twice=true ;;
    --scatter) scatter=true ;;
    --set=*) settings+=("${option#--set=}") ;;
    *) check_options+=("$option") ;;
  esac
done
runs=(1 "$processes")
if $twice; then runs+=("${processes}_again"); fi
for run in "${runs[@]}"; do
  make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" \
    OUT="$work/np$run" NP="${run%_again}" MPIRUN="mpirun --oversubscribe" \
    SET="${settings[*]:-}" simulate
done
if $scatter; then
  tolerance=$(python3 -c "import sys, tomllib; print(tomllib.load(open(sys.argv[1], 'rb')).get('solver', {}).get('ppe_tolerance', 1e-6) / 10)" \
    "$source_dir/pipelines/$case_name/scene.smoke.toml")
  make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" \
    OUT="$work/np1_tight" SET="${settings[*]:-} solver.ppe_tolerance=$tolerance" simulate
  check_options+=(--scatter "$work/np1_tight")
fi
python3 "$source_dir/tests/pipelines/check_processes.py" "$work/np1" "$work/np$processes" \
  "$source_dir/pipelines/$case_name/scene.smoke.toml" ${check_options[@]+"${check_options[@]}"}
if $twice; then  # the same process count twice: bit for bit (but the wall-clock timings)
  cmp "$work/np$processes/probes.csv" "$work/np${processes}_again/probes.csv"
  for dataset in $(h5ls -r "$work/np$processes/results.h5" | awk '$2 == "Dataset" {print $1}' |
                   grep -v -e seconds -e phase); do
    h5diff -d 0 "$work/np$processes/results.h5" "$work/np${processes}_again/results.h5" \
      "$dataset" "$dataset" || { echo "twice at $processes processes: $dataset differs"; exit 1; }
  done
  echo "twice at $processes processes: probes.csv and results.h5 identical"
fi
