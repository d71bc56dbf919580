// fsi-study STUDY --make-rules -o runs.mk — the runs of a speed-against-error study as make
// variables (pipelines/studies/study.mk includes them);
// fsi-study STUDY --runs DIR -o DIR/study/study.json — the finished runs tabulated and plotted:
// time to solution against the error, per series (study.md, study.json, PNG by gnuplot).
#include <filesystem>
#include <fstream>

#include "driver/study_stage.hpp"
#include "io/atomic_file.hpp"
#include "stage_main.hpp"

namespace {

void write_make_rules(const hm::driver::Study& study, const std::filesystem::path& output) {
  if (!output.parent_path().empty()) std::filesystem::create_directories(output.parent_path());
  hm::io::AtomicOutput file(output);
  {
    std::ofstream out(file.temp_path());
    out << hm::driver::study_make_rules(study);
    if (!out) throw hm::InputError("fsi-study: cannot write " + output.string());
  }
  file.commit();
}

}  // namespace

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-study",
      .summary =
          "Speed against error: tabulate and plot, per series of a study file, the time to "
          "solution of each run against its error (against the reference and against the "
          "series' finest run), or print the study's runs as make variables (--make-rules).",
      .positional = "STUDY",
      .positional_help = "study file (TOML; see pipelines/studies/README.md)",
      .inputs = {{"runs", "folder holding the runs, <series>/<run>/results.h5"}},
      .flags = {{"make-rules", "write the runs as make variables to the output and exit"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::driver::Study study = hm::driver::load_study(args.positional);
    if (args.validate) return;  // load_study checked the study and every run's scene
    if (args.output.empty()) throw hm::UsageError("fsi-study: -o/--output FILE is required");
    if (args.flags.at("make-rules")) return write_make_rules(study, args.output);
    if (args.inputs.at("runs").empty())
      throw hm::UsageError("fsi-study: --runs DIR is required (or --make-rules)");
    hm::driver::run_study_stage(study, args.inputs.at("runs"), args.output);
  });
}
