// fsi-map SCENE --modes modes.h5 -o mapped.h5 — mode shapes onto the surface the fluid sees.
#include "driver/map_stage.hpp"
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-map",
      .summary =
          "Interpolate mode shapes from the structure's surface onto the fluid-side surface "
          "(RBF, Wendland C2 + linear polynomial) into a hydromodal.mapped_modes artefact.",
      .inputs = {{"modes", "mode artefact written by fsi-modes"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    spdlog::info("fsi-map: resolved parameters of {}:\n{}", args.positional,
                 scene.parameters_for("fsi-map"));
    if (args.validate) {
      hm::driver::validate_map_scene(scene);
      spdlog::info("fsi-map: {} is valid for this stage", args.positional);
      return;
    }
    if (args.output.empty()) throw hm::UsageError("fsi-map: -o/--output FILE is required");
    if (args.inputs.at("modes").empty()) throw hm::UsageError("fsi-map: --modes FILE is required");
    hm::driver::run_map_stage(scene, args.inputs.at("modes"), args.output);
  });
}
