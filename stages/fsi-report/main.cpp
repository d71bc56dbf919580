// fsi-report — Plot probes against reference data and tabulate errors. The stage is not available
// in this version: its command line and scene validation exist so pipelines and scripts can be
// written against them.
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-report",
      .summary =
          "Plot probes against reference data and tabulate errors (not available in this version).",
      .inputs = {{"results", "results artefact written by fsi-simulate"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    if (args.validate) {
      spdlog::info("fsi-report: {} is a valid scene", args.positional);
      return;
    }
    throw hm::UsageError("fsi-report is not available in this version of hydromodal");
  });
}
