#!/usr/bin/env bash
# generated_docs.sh SOURCE_DIR BUILD_DIR
# docs/scene-keys.md and docs/artefact-schemas.md are the generated references (README links to
# them): they must be what the stages print now, so a new or changed key or dataset is documented
# in the same commit.
set -euo pipefail
source_dir="$1"; build_dir="$2"
check() {
  local file="$1"; shift
  if ! diff -u "$source_dir/$file" <("$@") > /dev/null; then
    diff -u "$source_dir/$file" <("$@") | head -40
    echo "generated_docs: $file is out of date; regenerate it with: $* > $file"
    exit 1
  fi
}
check docs/scene-keys.md "$build_dir/stages/fsi-mesh/fsi-mesh" --print-config-reference
check docs/artefact-schemas.md "$build_dir/stages/fsi-inspect/fsi-inspect" --print-schemas
echo "generated_docs: docs/scene-keys.md and docs/artefact-schemas.md are current"
