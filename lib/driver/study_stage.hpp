#pragma once
// fsi-study: speed against error. A study file names a case's scene, one probe column and one of
// its [[report.compare]] references, and series of runs, each run a list of scene-key settings
// (fluid.dx at several resolutions, modes.count at several mode counts). pipelines/studies/
// study.mk makes every run with the case's pipeline (`--set`), and fsi-study then tabulates and
// plots, per series, the time to solution against
//   the error against the reference: peak error, time-of-peak error and RMS / |reference peak|
//     over report.window, as fsi-report measures them;
//   the difference from the series' last run, its best estimate (runs are listed coarse → fine):
//     RMS / |peak of the last run| over the same window; and the observed order between
//     consecutive runs, ln(e_k/e_{k+1}) / |ln(v_k/v_{k+1})|, v the varied value.
// The time to solution is fsi-simulate's wall time plus fsi-modes' (factorisation and Lanczos).
//
// Study file (TOML; paths relative to it):
//   scene = "../../elastic_gate/scene.toml"      the case
//   column = "tip.ux [m]"                        the probe column measured
//   reference = "experiment (Antoci 2007)"       a [[report.compare]] label of that column
//   set = ["time.end=0.4"]                       settings of every run (optional)
//   [[series]]
//   name = "resolution"                          [A-Za-z0-9._-]+, as are the run names
//   parameter = "fluid.dx"                       the key that varies, set by every run
//   set = [...]                                  settings of every run of the series (optional)
//   runs = [{ name = "dx5", set = ["fluid.dx=0.005"] }, ...]
#include <filesystem>
#include <string>
#include <vector>

namespace hm::driver {

struct StudyRun {
  std::string name;
  std::vector<std::string> set;  ///< every setting of the run: study's, series', run's
  std::string value;             ///< the text of the series' parameter in the run's settings
};

struct StudySeries {
  std::string name, parameter;
  std::vector<StudyRun> runs;
};

struct Study {
  std::filesystem::path file, scene;
  std::string column, reference;
  std::vector<StudySeries> series;
};

/// Reads and checks a study file; InputError naming the file, key and bad value.
Study load_study(const std::filesystem::path& file);

/// Make variables for study.mk: STUDY_SCENE, STUDY_CASE_DIR, STUDY_RUNS (series/run) and
/// STUDY_SET.<series>/<run> (the run's settings, blank-separated).
std::string study_make_rules(const Study& study);

/// The observed order between two runs: ln(e0/e1) / |ln(v0/v1)|; NaN when undefined.
double observed_order(double value0, double error0, double value1, double error1);

/// Tabulates and plots the finished runs in `runs`/<series>/<run>/ into the folder of `output`
/// (output = <folder>/study.json; also study.md and per series <series>.cost.png and
/// <series>.curves.png). InputError naming the run when a run has no results.
void run_study_stage(const Study& study, const std::filesystem::path& runs,
                     const std::filesystem::path& output);

}  // namespace hm::driver
