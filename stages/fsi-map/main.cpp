// fsi-map SCENE --modes modes.h5 -o mapped.h5 — mode shapes onto the surface the fluid sees.
#include "driver/map_stage.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-map",
      .summary =
          "Interpolate mode shapes from the structure's surface onto the fluid-side surface "
          "(RBF, Wendland C2 + linear polynomial) into a hydromodal.mapped_modes artefact.",
      .inputs = {{"modes", "mode artefact written by fsi-modes"}},
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = hm::driver::validate_map_scene,
       .run = [](const hm::io::Scene& scene, const auto& inputs, const std::string& output) {
         hm::driver::run_map_stage(scene, inputs.at("modes"), output);
       }});
}
