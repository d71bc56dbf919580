// fsi-simulate SCENE --mesh mesh.h5 [--mapped mapped.h5 | --modes modes.h5] -o
// out/<case>/<variant>/results.h5 — the LDD free-surface flow with rigid walls (fixed or in
// prescribed motion) and, in a scene with a [structure], the structure as a flexible body coupled
// two-way (--mapped), or a structure-only run (loads on the modes, --modes); probes.csv and
// snapshots/ are written next to results.h5. The scene-stage shape of stage_main (echo, --validate,
// --if-stale), with optional inputs: without --mesh the walls are meshed from the scene (fsi-mesh
// needs a [structure]).
#include "driver/flow_setup.hpp"
#include "driver/simulate_stage.hpp"
#include "io/artefact.hpp"
#include "linsolve/linear_solver.hpp"
#include "stage_main.hpp"

namespace {

constexpr const char* name = "fsi-simulate";

void simulate(const hm::stages::StageArgs& args) {
  const hm::io::Scene scene = hm::io::Scene::load(args.positional, args.overrides);
  hm::stages::log_overrides(name, args.overrides);
  spdlog::info("{}: resolved parameters of {}:\n{}", name, args.positional,
               scene.parameters_for(name));
  if (args.validate) {
    hm::driver::validate_simulate_scene(scene);
    hm::driver::validate_flow_geometry(scene);
    spdlog::info("{}: {} is valid for this stage", name, args.positional);
    return;
  }
  if (args.output.empty())
    throw hm::UsageError(std::string(name) + ": -o/--output FILE is required");
  std::map<std::string, std::string> given;
  for (const auto& [input, path] : args.inputs)
    if (!path.empty()) given.emplace(input, path);
  if (args.flags.at("if-stale")) {
    const std::string reason = hm::io::staleness(
        args.output, name, hm::driver::simulate_parameters(scene, args.inputs.at("mesh").empty()),
        given);
    if (reason.empty()) {
      spdlog::info("{}: {} is up to date", name, args.output);
      return;
    }
    spdlog::info("{}: (re)making {}: {}", name, args.output, reason);
  }
  hm::driver::run_simulate_stage(scene,
                                 {.mesh = args.inputs.at("mesh"),
                                  .mapped = args.inputs.at("mapped"),
                                  .modes = args.inputs.at("modes"),
                                  .restart = args.inputs.at("restart")},
                                 args.output);
}

}  // namespace

/// The PPE solvers of this build (solver.preconditioner), for --version.
std::string solver_list() {
  std::string list = "PPE solvers (solver.preconditioner): automatic";
  for (const auto m : hm::linsolve::available_methods())
    list += std::string(", ") + hm::linsolve::to_string(m);
  return list;
}

int main(int argc, char** argv) {
  const hm::stages::StageInfo info{
      .name = name,
      .summary =
          "Run the LDD free-surface flow with rigid walls (fixed or in prescribed motion) and "
          "the structure coupled two-way (explicit or strong, [coupling]), or the structure "
          "alone under prescribed loads (CFPI on its modes): results.h5 "
          "(hydromodal.results), probes.csv (and snapshots/ of a flow) next to it.",
      .inputs = {{"mesh",
                  "mesh artefact written by fsi-mesh (the walls); without it the [[wall]]s are "
                  "meshed from the scene as fsi-mesh would (rigid-only scenes)"},
                 {"mapped",
                  "mapped-modes artefact written by fsi-map: the flexible body of a scene with "
                  "[fluid] and [structure] (its surface becomes the wall \"structure\")"},
                 {"modes",
                  "modes artefact written by fsi-modes: the structure of a structure-only run "
                  "(a scene with [[load]]s and no [fluid]; needs --mesh for the node groups), or "
                  "the interface modes of a coupled run with structure.model = \"nonlinear_fe\""},
                 {"restart",
                  "checkpoint of this scene's run (checkpoints/t_<time>.h5, written every "
                  "time.checkpoint_interval): continue from it; with the same inputs the result "
                  "is the uninterrupted run's (time.end may be changed to run on)"}},
      .flags = {{"if-stale",
                 "run only if the output is missing or stale: written by another tool version, "
                 "with other scene parameters, or from inputs whose content changed (content "
                 "hashes decide, not timestamps)"}},
      .version_details = solver_list(),
  };
  return hm::stages::run_stage(argc, argv, info, simulate);
}
