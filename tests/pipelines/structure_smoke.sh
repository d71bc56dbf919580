#!/usr/bin/env bash
# structure_smoke.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE
# Runs the smoke variant of a structure-only pipeline (make VARIANT=smoke: mesh → modes →
# simulate) with the stages of BUILD_DIR into WORK_DIR, then checks that results.h5 completed and
# probes.csv has its header and a row per step. The numbers are checked in tests/driver
# (test_structure_run: the cantilever against the analytic response).
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"
rm -rf "$work"; mkdir -p "$work"
make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" OUT="$work"
summary=$("$build_dir/stages/fsi-inspect/fsi-inspect" --json "$work/results.h5")
grep -q '"run_status": "completed"' <<< "$summary"
grep -q '^t \[s\],' < "$work/probes.csv"
rows=$(($(wc -l < "$work/probes.csv") - 1))
echo "$case_name smoke: completed, $rows probe rows"
test "$rows" -gt 1
