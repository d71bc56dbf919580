#!/usr/bin/env bash
# restart_equivalence.sh FSI_SIMULATE WORK SCENE [fsi-simulate inputs...]
# Runs SCENE (which sets time.checkpoint_interval) to its end in WORK/A, copies the folder to
# WORK/B and restarts there from the first checkpoint: the probe CSV must be byte for byte the
# uninterrupted run's and every dataset of results.h5 but the wall-clock timings equal to the
# last bit (h5diff -d 0); a checkpoint of a scene with other parameters must be refused (exit 2).
set -euo pipefail
simulate="$1"; work="$2"; scene="$3"; shift 3
rm -rf "$work"; mkdir -p "$work/A"
OMP_NUM_THREADS=1 "$simulate" "$scene" "$@" -o "$work/A/results.h5" -q
first=$(ls "$work/A/checkpoints" | sort | head -1)
test -n "$first"
cp -r "$work/A" "$work/B"
OMP_NUM_THREADS=1 "$simulate" "$scene" "$@" --restart "$work/B/checkpoints/$first" \
  -o "$work/B/results.h5" -q
cmp "$work/A/probes.csv" "$work/B/probes.csv"
for dataset in $(h5ls -r "$work/A/results.h5" | awk '$2 == "Dataset" {print $1}' |
                 grep -v -e seconds -e phase); do
  h5diff -d 0 "$work/A/results.h5" "$work/B/results.h5" "$dataset" "$dataset" ||
    { echo "restart: $dataset differs"; exit 1; }
done
echo "restart from $first: probes.csv and results.h5 identical to the uninterrupted run"
# Another scene's checkpoint: refused.
sed 's/^dx = \(.*\)/dx = 0.0123/' "$scene" > "$work/other.toml"
set +e
out=$(OMP_NUM_THREADS=1 "$simulate" "$work/other.toml" "$@" --restart "$work/B/checkpoints/$first" \
        -o "$work/C/results.h5" 2>&1)
code=$?
set -e
echo "$out" | tail -1
test "$code" = 2
echo "$out" | grep -q "written for other scene parameters"
