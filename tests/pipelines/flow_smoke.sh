#!/usr/bin/env bash
# flow_smoke.sh SOURCE_DIR BUILD_DIR WORK_DIR CASE
# Runs the smoke variant of the flow pipeline pipelines/CASE (make ... VARIANT=smoke simulate
# report: the report's plots and tables must appear)
# with the stages of BUILD_DIR into the scratch folder WORK_DIR (OUT=WORK_DIR, not out/), then
# checks its results.h5 and probes.csv against the case's stated tolerances
# (check_flow_smoke.py). A diverged run fails make (fsi-simulate exits 3) and so the test.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"; case_name="$4"
rm -rf "$work"; mkdir -p "$work"
make -C "$source_dir/pipelines/$case_name" VARIANT=smoke HM_BUILD="$build_dir" OUT="$work" simulate report
test -s "$work/report/metrics.md" && test -s "$work/report/monitors.png"
python3 "$source_dir/tests/pipelines/check_flow_smoke.py" "$case_name" "$work" \
  "$source_dir/pipelines/$case_name/scene.smoke.toml" "$source_dir" "$build_dir"
