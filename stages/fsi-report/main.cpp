// fsi-report SCENE --results results.h5 -o report/metrics.h5 — plots of every probe against its
// reference curves, the structure's response and the run monitors (PNG, gnuplot), and the error
// metrics (metrics.h5, metrics.json, metrics.md) in the folder of the output.
#include "driver/report_stage.hpp"
#include "stage_main.hpp"

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = "fsi-report",
      .summary =
          "Plot every probe against the scene's reference curves ([[report.compare]]), the "
          "structure's modal response and the run monitors, and tabulate peak, time-of-peak and "
          "RMS errors (metrics.h5, metrics.json, metrics.md; PNG by gnuplot) in the output's "
          "folder.",
      .inputs = {{"results", "results artefact written by fsi-simulate"}},
  };
  return hm::stages::run_scene_stage(
      argc, argv, info,
      {.validate = hm::driver::validate_report_scene,
       .run = [](const hm::io::Scene& scene, const auto& inputs, const std::string& output) {
         hm::driver::run_report_stage(scene, inputs.at("results"), output);
       }});
}
