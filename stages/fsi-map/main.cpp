// fsi-map — Map mode shapes onto fluid wall surfaces (RBF). The stage is not available in this version: its
// command line and scene validation exist so pipelines and scripts can be written against them.
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-map",
      .summary = "Map mode shapes onto fluid wall surfaces (RBF) (not available in this version).",
      .inputs = {{"modes", "mode artefact written by fsi-modes"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    if (args.validate) {
      spdlog::info("fsi-map: {} is a valid scene", args.positional);
      return;
    }
    throw hm::UsageError("fsi-map is not available in this version of hydromodal");
  });
}
