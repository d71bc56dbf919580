// fsi-simulate — Run the coupled LDD flow + modal structure simulation. The stage is not available
// in this version: its command line and scene validation exist so pipelines and scripts can be
// written against them.
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-simulate",
      .summary =
          "Run the coupled LDD flow + modal structure simulation (not available in this version).",
      .inputs = {{"mapped", "mapped-modes artefact written by fsi-map"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    if (args.validate) {
      spdlog::info("fsi-simulate: {} is a valid scene", args.positional);
      return;
    }
    throw hm::UsageError("fsi-simulate is not available in this version of hydromodal");
  });
}
