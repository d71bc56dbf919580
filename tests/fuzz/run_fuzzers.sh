#!/usr/bin/env bash
# run_fuzzers.sh BUILD_DIR SECONDS [HARNESS...] — runs each libFuzzer harness (default: scene csv
# surface artefact) of BUILD_DIR (the `fuzz` preset: cmake --preset fuzz && cmake --build --preset
# fuzz) for SECONDS of fuzzing, after replaying its regression inputs
# (tests/fuzz/regressions/<harness>/, the inputs of defects found and fixed). Seed corpora come
# from the repository's own files: scenes (pipelines, stage tests), time tables and reference
# curves, surface files (and a small OBJ, PLY, open and binary STL written here), and small valid
# artefacts of each schema (tests/fuzz/seeds/artefact/, each behind every schema's selector byte).
# The corpus grows in BUILD_DIR/fuzz-work/<harness>/corpus across runs; a crash, leak, hang
# (> 20 s an input) or sanitizer report is written to .../crashes/ and fails the script. Prints
# executions and time per harness.
set -euo pipefail
build="$(cd "$1" && pwd)"; seconds="$2"; shift 2
harnesses=("$@"); [ ${#harnesses[@]} -gt 0 ] || harnesses=(scene csv surface artefact)
source_dir="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# Leaks inside libraries on malformed input, each with its upstream report (lsan.supp).
export LSAN_OPTIONS="suppressions=$source_dir/tests/fuzz/lsan.supp:print_suppressions=0"
export OMP_NUM_THREADS=1

# A seed: the file's bytes behind one selector byte (the harness's choice of reader).
seed() { local selector="$1" file="$2" out="$3"; { printf "\\x$selector"; cat "$file"; } > "$out"; }

make_seeds() {
  local harness="$1" dir="$2" k=0
  mkdir -p "$dir"
  case "$harness" in
    scene)
      for f in "$source_dir"/pipelines/*/*.toml "$source_dir"/pipelines/studies/*/*.toml \
               "$source_dir"/tests/stages/scenes/*.toml "$source_dir"/tests/stages/data/*.toml; do
        [ -f "$f" ] && cp "$f" "$dir/$((k++)).toml"
      done
      printf '#set fluid.dx=0.02\n#set wall[0].mesh_size=0.01\n' | cat - "$source_dir/tests/stages/data/hydrostatic_small.toml" > "$dir/overrides.toml" ;;
    csv)
      while IFS= read -r f; do
        seed 00 "$f" "$dir/$((k++))"; seed 02 "$f" "$dir/$((k++))"
      done < <(find "$source_dir/data/reference" "$source_dir/pipelines" "$source_dir/tests" -name '*.csv' | head -n 60)
      printf 't [s],factor [1]\n0,0\n0.5,1\n1,1\n' > "$dir/load.raw"; seed 01 "$dir/load.raw" "$dir/load"; rm "$dir/load.raw"
      printf 't [s],p.p [Pa],g.eta [m]\n0,1,nan\n0.1,2,0.3\n' > "$dir/probes.raw"; seed 02 "$dir/probes.raw" "$dir/probes"; rm "$dir/probes.raw" ;;
    surface)
      for f in "$source_dir"/data/geometry/*.stl; do seed 00 "$f" "$dir/$((k++))"; done
      printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n' > "$dir/tet.obj"
      seed 01 "$dir/tet.obj" "$dir/obj"; rm "$dir/tet.obj"
      printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n' > "$dir/tet.ply"
      seed 02 "$dir/tet.ply" "$dir/ply"; rm "$dir/tet.ply"
      printf 'solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n' > "$dir/open.stl"
      seed 00 "$dir/open.stl" "$dir/open"; rm "$dir/open.stl"
      python3 - "$dir/binary" <<'PY'
import struct, sys
v = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
faces = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (0, 3, 2)]
body = b"".join(struct.pack("<12fH", 0, 0, 0, *v[a], *v[b], *v[c], 0) for a, b, c in faces)
open(sys.argv[1], "wb").write(b"\x00" + b"binary tetrahedron".ljust(80, b" ") + struct.pack("<I", len(faces)) + body)
PY
      ;;
    artefact)
      # The selector picks the schema expected (io::all_schemas order): every artefact behind
      # every selector, so the wrong-schema paths are seeded too.
      for f in "$source_dir"/tests/fuzz/seeds/artefact/*.h5; do
        for selector in 00 01 02 03 04 05; do seed "$selector" "$f" "$dir/$((k++))"; done
      done ;;
  esac
}

status=0
for harness in "${harnesses[@]}"; do
  binary="$build/tests/fuzz/fuzz_$harness"
  [ -x "$binary" ] || { echo "run_fuzzers: $binary missing: cmake --build --preset fuzz" >&2; exit 1; }
  work="$build/fuzz-work/$harness"
  rm -rf "$work/seeds"; make_seeds "$harness" "$work/seeds"
  mkdir -p "$work/corpus" "$work/crashes"
  regressions="$source_dir/tests/fuzz/regressions/$harness"
  if [ -d "$regressions" ] && [ -n "$(ls -A "$regressions")" ]; then
    "$binary" "$regressions"/* > "$work/regressions.log" 2>&1 ||
      { echo "run_fuzzers: $harness: a regression input fails again (see $work/regressions.log)"; status=1; continue; }
  fi
  start=$(date +%s)
  if "$binary" "$work/corpus" "$work/seeds" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 \
       -artifact_prefix="$work/crashes/" -print_final_stats=1 > "$work/fuzz.log" 2>&1; then
    result=ok
  else
    result="FAILED (see $work/fuzz.log and $work/crashes/)"; status=1
  fi
  runs=$(grep -Eo 'stat::number_of_executed_units: [0-9]+' "$work/fuzz.log" | grep -Eo '[0-9]+$' || echo "?")
  echo "run_fuzzers: $harness: $result, $runs executions in $(( $(date +%s) - start )) s, corpus $(ls "$work/corpus" | wc -l) inputs"
done
exit $status
