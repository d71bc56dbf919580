#!/usr/bin/env bash
# mode_archive.sh BIN_DIR SOURCE_DIR WORK_DIR
# The mode archive on the elastic gate: a computed set is archived (make archive), a scene that
# names it (modes.archived) gets it back from fsi-modes byte for byte without solving, and a
# scene whose material or mesh no longer matches is refused with exit 2 naming the difference.
set -euo pipefail
bin="$1"; source_dir="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work/archive"
gate="$source_dir/pipelines/elastic_gate"
cp "$gate/scene.smoke.toml" "$work/scene.toml"; cp "$gate/dam_wall.geo" "$work/"
sed -i 's|\.\./\.\./data/|'"$source_dir"'/data/|' "$work/scene.toml"
"$bin/fsi-mesh/fsi-mesh" "$work/scene.toml" -o "$work/mesh.h5" --quiet
"$bin/fsi-modes/fsi-modes" "$work/scene.toml" --mesh "$work/mesh.h5" -o "$work/modes.h5" --quiet
make -s -C "$gate" archive VARIANT=smoke OUT="$work" ARCHIVE="$work/archive" NAME=test \
  HM_BUILD="$(dirname "$bin")" \
  > /dev/null
archived="$work/archive/elastic_gate-test.modes.h5"
test -s "$archived"
# Reuse: a scene that names the archived set.
sed 's|^\[modes\]|[modes]\narchived = "'"$archived"'"|' "$work/scene.toml" > "$work/reuse.toml"
"$bin/fsi-modes/fsi-modes" "$work/reuse.toml" --mesh "$work/mesh.h5" -o "$work/reused.h5" \
  2>&1 | grep -q "reused the archived mode set"
cmp "$archived" "$work/reused.h5"
# Another material: refused, naming the key.
sed 's|^youngs_modulus = 12e6 .*|youngs_modulus = 13e6|' "$work/reuse.toml" > "$work/stiffer.toml"
set +e
out="$("$bin/fsi-modes/fsi-modes" "$work/stiffer.toml" --mesh "$work/mesh.h5" -o "$work/x.h5" 2>&1)"
code=$?
set -e
[ "$code" = 2 ] || { echo "material change: exit $code, expected 2"; echo "$out"; exit 1; }
echo "$out" | grep -q "structure.material.youngs_modulus = 13000000" ||
  { echo "material change: the message does not name the key"; echo "$out"; exit 1; }
[ ! -e "$work/x.h5" ] || { echo "a refused reuse left an output"; exit 1; }
# Another mesh: refused.
sed 's|^size = 0.0025 .*|size = 0.002|' "$work/scene.toml" > "$work/finer.toml"
"$bin/fsi-mesh/fsi-mesh" "$work/finer.toml" -o "$work/finer_mesh.h5" --quiet
set +e
out="$("$bin/fsi-modes/fsi-modes" "$work/reuse.toml" --mesh "$work/finer_mesh.h5" -o "$work/y.h5" 2>&1)"
code=$?
set -e
[ "$code" = 2 ] && echo "$out" | grep -q "another geometry or mesh" ||
  { echo "mesh change: exit $code"; echo "$out"; exit 1; }
echo "mode archive: reuse byte for byte, material and mesh changes refused"
