#!/usr/bin/env bash
# study_smoke.sh SOURCE_DIR BUILD_DIR WORK_DIR
# The elastic gate's speed-against-error study, smoke variant (pipelines/studies/elastic_gate/
# study.smoke.toml: two resolutions, two mode counts), into WORK_DIR: every run is made with its
# --set overrides, the table and plots appear, each run's results carry its own settings, a second
# make reruns no stage, and a study with a bad setting is refused (exit 2) before any run.
set -euo pipefail
source_dir="$1"; build_dir="$2"; work="$3"
rm -rf "$work"; mkdir -p "$work"
study="$source_dir/pipelines/studies/elastic_gate"
make_study() { make -C "$study" VARIANT=smoke HM_BUILD="$build_dir" STUDY_OUT="$work" "$@" 2>&1; }
fail() { echo "study_smoke: $*"; exit 1; }

first="$(make_study)" || { echo "$first"; fail "the study failed"; }
for png in resolution.cost resolution.curves modes.cost modes.curves; do
  head -c 8 "$work/study/$png.png" | grep -q PNG || fail "no $png.png"
done
grep -q "^| dx6 | 0.006 |" "$work/study/study.md" || fail "no row of run dx6 in study.md"

python3 - "$work" "$build_dir" <<'PY'
import json, subprocess, sys
work, build = sys.argv[1], sys.argv[2]
study = json.load(open(f"{work}/study/study.json"))
assert [s["name"] for s in study["series"]] == ["resolution", "modes"], study["series"]
for series in study["series"]:
    runs = series["runs"]
    assert len(runs) == 2, runs
    for run in runs:
        assert run["status"] == "completed", run
        assert run["time_to_solution_s"] > 0 and run["steps"] > 0, run
        ref = run["vs_reference"]
        assert all(abs(ref[k]) < 10 for k in ("peak_error", "rms_relative")), ref
    # The last run is the series' estimate: zero against itself, not against the first.
    assert runs[-1]["vs_last"]["rms"] == 0.0 and runs[0]["vs_last"]["rms"] > 0.0, runs
# Each run's artefacts carry its own settings (the provenance records the --set values).
def parameters(path):
    out = subprocess.run([f"{build}/stages/fsi-inspect/fsi-inspect", "--json", path],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["attributes"]["parameters"]
res = {r["name"]: r for r in study["series"][0]["runs"]}
assert "fluid.dx = 0.006" in parameters(res["dx6"]["folder"] + "/results.h5")
assert "fluid.dx = 0.005" in parameters(res["dx5"]["folder"] + "/results.h5")
modes = {r["name"]: r for r in study["series"][1]["runs"]}
assert "modes.count = 2" in parameters(modes["m2"]["folder"] + "/modes.h5")
# More points, more steps: the finer run costs more.
assert res["dx5"]["points"] > res["dx6"]["points"], res
print("study_smoke: study.json holds both series, each run with its own settings")
PY

second="$(make_study)" || { echo "$second"; fail "the second make failed"; }
if grep -Eq "\(re\)making" <<<"$second"; then echo "$second"; fail "a second make reran a stage"; fi

# A run whose settings changed after it was made (its remake failed, or was not made) is refused
# by the table, not tabulated with its old results.
changed="$work/changed.toml"
sed -e 's/fluid.dx=0.006"\]/fluid.dx=0.0065"]/' \
    -e "s|^scene = \"../../|scene = \"$source_dir/pipelines/|" "$study/study.smoke.toml" > "$changed"
set +e
message="$("$build_dir/stages/fsi-study/fsi-study" "$changed" --runs "$work" -o "$work/changed/study.json" 2>&1)"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "$message"; fail "a stale run was tabulated (exit $code)"; }
grep -q "run resolution/dx6 is stale" <<<"$message" || { echo "$message"; fail "no stale message"; }
[ ! -e "$work/changed" ] || fail "a refused table left $work/changed"

bad="$work/bad.toml"
sed -e 's/fluid.dx=0.006"\]/fluid.dx=-1"]/' \
    -e "s|^scene = \"../../|scene = \"$source_dir/pipelines/|" "$study/study.smoke.toml" > "$bad"
set +e
message="$("$build_dir/stages/fsi-study/fsi-study" "$bad" --make-rules -o "$work/bad.mk" 2>&1)"
code=$?
set -e
[ "$code" -eq 2 ] || { echo "$message"; fail "a bad setting exited $code, expected 2"; }
grep -q "fluid.dx = -1 is out of range" <<<"$message" || { echo "$message"; fail "no message"; }
[ ! -e "$work/bad.mk" ] || fail "a refused study left $work/bad.mk"
echo "study_smoke: second make reran nothing; a bad setting was refused with exit 2"

# kill -9 of fsi-study at several moments (issue 19, item 7): its folder then holds nothing or
# the complete table (study.json parses, every plot is a whole PNG), never a part of one.
study_file="$work/study.toml"
sed -e "s|^scene = \"../../|scene = \"$source_dir/pipelines/|" "$study/study.smoke.toml" > "$study_file"
for delay in 0.05 0.2 0.5 1; do
  out="$work/killed/study"
  rm -rf "$work/killed"
  "$build_dir/stages/fsi-study/fsi-study" "$study_file" --runs "$work" -o "$out/study.json" -q \
    > /dev/null 2>&1 &
  pid=$!
  sleep "$delay"
  kill -9 "$pid" 2> /dev/null || true
  wait "$pid" 2> /dev/null || true
  # The folder appears whole (staged beside it, then renamed): absent, or the table, its JSON
  # and plots all there.
  if [ -e "$out" ]; then
    [ -f "$out/study.md" ] && [ -f "$out/study.json" ] ||
      fail "fsi-study killed after $delay s left $out without its table"
    python3 -c "import json, sys; json.load(open(sys.argv[1]))" "$out/study.json" ||
      fail "fsi-study killed after $delay s left a partial study.json"
    for png in resolution.cost resolution.curves modes.cost modes.curves; do
      [ -f "$out/$png.png" ] || fail "fsi-study killed after $delay s left $out without $png.png"
    done
  fi
  for png in "$out"/*.png; do
    [ -e "$png" ] || continue
    python3 - "$png" <<'PY' || fail "fsi-study killed after $delay s left a partial $png"
import sys
data = open(sys.argv[1], "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[-12:-4] == b"\x00\x00\x00\x00IEND", sys.argv[1]
PY
  done
  echo "study_smoke: fsi-study killed after $delay s: $( [ -e "$out" ] && echo "the whole folder" || echo "no folder"), nothing partial"
done
