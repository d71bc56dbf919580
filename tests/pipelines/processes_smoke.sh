#!/usr/bin/env bash
# processes_smoke.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE NP [--until-impact]
# The smoke variant of the flow pipeline pipelines/CASE run as one process (NP=1) and over NP
# MPI processes (make NP=NP: mpirun -np NP fsi-simulate), each into its own scratch folder;
# check_processes.py then holds every probe of the NP run to the one-process run within 10× the
# PPE tolerance of the probe's largest value (with --until-impact: up to the impact, after which
# a violent flow is chaotic; the time the runs part is printed), and the NP run to have
# completed. Run as root
# (CI), OpenMPI needs OMPI_ALLOW_RUN_AS_ROOT(_CONFIRM)=1, set here; --oversubscribe lets NP
# exceed the cores.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"; processes="$5"; shift 5
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1
rm -rf "$work"; mkdir -p "$work"
for np in 1 "$processes"; do
  make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" \
    OUT="$work/np$np" NP="$np" MPIRUN="mpirun --oversubscribe" simulate
done
python3 "$source_dir/tests/pipelines/check_processes.py" "$work/np1" "$work/np$processes" \
  "$source_dir/pipelines/$case_name/scene.smoke.toml" "$@"
