// fsi-simulate — Run the coupled LDD flow + modal structure simulation. Not available in this
// version: its command line and scene validation exist so that pipelines and scripts can be written
// against them.
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-simulate",
      .summary =
          "Run the coupled LDD flow + modal structure simulation (not available in this version).",
      .inputs = {{"mapped", "mapped-modes artefact written by fsi-map"}},
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = [](const hm::io::Scene&) {},
       .run =
           [](const hm::io::Scene&, const auto&, const std::string&) {
             throw hm::UsageError("fsi-simulate is not available in this version of hydromodal");
           }});
}
