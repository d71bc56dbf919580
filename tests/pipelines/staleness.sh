#!/usr/bin/env bash
# staleness.sh SOURCE_DIR BUILD_DIR WORK_DIR
# The elastic-gate pipeline in a scratch copy: a first make builds everything; `touch` on the
# scene reruns nothing; an edited Young's modulus reruns fsi-modes and fsi-map but not fsi-mesh.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work/pipelines"
cp "$source_dir/pipelines/common.mk" "$work/pipelines/"
cp -r "$source_dir/pipelines/elastic_gate" "$work/pipelines/"
run() { make -C "$work/pipelines/elastic_gate" HM_BUILD="$build_dir" map 2>&1; }
expect() { grep -Eq -- "$2" <<<"$1" || { echo "staleness: expected /$2/ in:"; echo "$1"; exit 1; }; }
reject() { ! grep -Eq -- "$2" <<<"$1" || { echo "staleness: unexpected /$2/ in:"; echo "$1"; exit 1; }; }

first="$(run)"
expect "$first" "fsi-mesh: \(re\)making .*mesh.h5: it does not exist"
expect "$first" "fsi-map: \(re\)making .*mapped.h5: it does not exist"

sleep 1; touch "$work/pipelines/elastic_gate/scene.toml"
touched="$(run)"
for artefact in mesh modes mapped; do expect "$touched" "$artefact.h5 is up to date"; done
reject "$touched" "\(re\)making"

sed -i 's/^youngs_modulus = 12e6/youngs_modulus = 11e6/' "$work/pipelines/elastic_gate/scene.toml"
edited="$(run)"
expect "$edited" "mesh.h5 is up to date"
expect "$edited" "fsi-modes: \(re\)making .*modes.h5: the scene parameters changed"
expect "$edited" "fsi-map: \(re\)making .*mapped.h5: the content of input 'modes'"
echo "staleness: touch reran nothing; a material edit reran modes and map, not mesh"
