#!/usr/bin/env bash
# staleness.sh SOURCE_DIR BUILD_DIR WORK_DIR
# The elastic-gate pipeline (smoke variant, every stage through the report) in a scratch copy: a
# first make builds everything; `touch` on the scene reruns nothing; an edited Young's modulus
# reruns fsi-modes and everything after it (map, simulate, report) but not fsi-mesh; the same edit
# given as `make SET=...` instead is a change of parameters too.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work/pipelines"
cp "$source_dir/pipelines/common.mk" "$work/pipelines/"
cp -r "$source_dir/pipelines/elastic_gate" "$work/pipelines/"
# The references of the report, where the scene's relative paths expect them.
mkdir -p "$work/data/reference"
cp -r "$source_dir/data/reference/antoci2007_elastic_gate" "$work/data/reference/"
scene="$work/pipelines/elastic_gate/scene.smoke.toml"
run() { make -C "$work/pipelines/elastic_gate" HM_BUILD="$build_dir" VARIANT=smoke "$@" 2>&1; }
stages="mesh modes mapped results report/metrics"
expect() { grep -Eq -- "$2" <<<"$1" || { echo "staleness: expected /$2/ in:"; echo "$1"; exit 1; }; }
reject() { ! grep -Eq -- "$2" <<<"$1" || { echo "staleness: unexpected /$2/ in:"; echo "$1"; exit 1; }; }

first="$(run)"
expect "$first" "fsi-mesh: \(re\)making .*mesh.h5: it does not exist"
expect "$first" "fsi-report: \(re\)making .*metrics.h5: it does not exist"

sleep 1; touch "$scene" "$work/pipelines/elastic_gate/dam_wall.geo"
touched="$(run)"
for artefact in $stages; do expect "$touched" "$artefact.h5 is up to date"; done
reject "$touched" "\(re\)making"

# The same edit as an override: every stage from fsi-modes on sees other parameters.
overridden="$(run SET=structure.material.youngs_modulus=11e6)"
expect "$overridden" "mesh.h5 is up to date"
expect "$overridden" "fsi-modes: \(re\)making .*modes.h5: the scene parameters changed"

sed -i 's/^youngs_modulus = 12e6/youngs_modulus = 11e6/' "$scene"
edited="$(run)"
expect "$edited" "mesh.h5 is up to date"
# The file now says what the override said: fsi-modes is up to date with the override's run.
expect "$edited" "modes.h5 is up to date"
sed -i 's/^youngs_modulus = 11e6/youngs_modulus = 10e6/' "$scene"
edited="$(run)"
expect "$edited" "mesh.h5 is up to date"
expect "$edited" "fsi-modes: \(re\)making .*modes.h5: the scene parameters changed"
expect "$edited" "fsi-map: \(re\)making .*mapped.h5: the content of input 'modes'"
expect "$edited" "fsi-simulate: \(re\)making .*results.h5: the content of input 'mapped'"
expect "$edited" "fsi-report: \(re\)making .*metrics.h5: the content of input 'results'"
echo "staleness: touch reran nothing; a material edit (in the file or by SET) reran modes, map,"
echo "staleness: simulate and report, not mesh"
