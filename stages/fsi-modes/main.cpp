// fsi-modes SCENE --mesh mesh.h5 -o modes.h5 — natural modes of the structure (FE + ARPACK).
#include "driver/modes_stage.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-modes",
      .summary =
          "Extract natural frequencies and mass-normalised mode shapes of the structure "
          "(linear elasticity, ARPACK shift-invert Lanczos) into a hydromodal.modes artefact.",
      .inputs = {{"mesh", "structure mesh artefact written by fsi-mesh"}},
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = hm::driver::validate_modes_scene,
       .run = [](const hm::io::Scene& scene, const auto& inputs, const std::string& output) {
         hm::driver::run_modes_stage(scene, inputs.at("mesh"), output);
       }});
}
