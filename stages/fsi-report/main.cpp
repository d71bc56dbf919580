// fsi-report — Plot probes against reference data and tabulate errors. Not available in this
// version: its command line and scene validation exist so that pipelines and scripts can be written
// against them.
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-report",
      .summary =
          "Plot probes against reference data and tabulate errors (not available in this version).",
      .inputs = {{"results", "results artefact written by fsi-simulate"}},
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = [](const hm::io::Scene&) {},
       .run =
           [](const hm::io::Scene&, const auto&, const std::string&) {
             throw hm::UsageError("fsi-report is not available in this version of hydromodal");
           }});
}
