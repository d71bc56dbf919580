// fsi-modes SCENE --mesh mesh.h5 -o modes.h5 — natural modes of the structure (FE + ARPACK).
#include "driver/modes_stage.hpp"
#include "io/scene.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-modes",
      .summary =
          "Extract natural frequencies and mass-normalised mode shapes of the structure "
          "(linear elasticity, ARPACK shift-invert Lanczos) into a hydromodal.modes artefact.",
      .inputs = {{"mesh", "structure mesh artefact written by fsi-mesh"}},
  };
  return hm::stages::run_stage(argc, argv, info, [](const hm::stages::StageArgs& args) {
    const hm::io::Scene scene = hm::io::Scene::load(args.positional);
    spdlog::info("fsi-modes: resolved parameters of {}:\n{}", args.positional,
                 scene.parameters_for("fsi-modes"));
    if (args.validate) {
      hm::driver::validate_modes_scene(scene);
      spdlog::info("fsi-modes: {} is valid for this stage", args.positional);
      return;
    }
    if (args.output.empty()) throw hm::UsageError("fsi-modes: -o/--output FILE is required");
    if (args.inputs.at("mesh").empty()) throw hm::UsageError("fsi-modes: --mesh FILE is required");
    hm::driver::run_modes_stage(scene, args.inputs.at("mesh"), args.output);
  });
}
