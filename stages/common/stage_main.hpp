#pragma once
// The one main() of every stage: parse arguments, set up logging and interrupt cleanup, call
// one library function, and map errors to the documented exit codes
//   0 ok · 1 usage · 2 invalid input · 3 numerical failure · 4 internal error (a bug).
// CLI11 is compiled once, in stage_main.cpp (it costs ~8 s per translation unit).
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "io/scene.hpp"

namespace hm::stages {

struct StageInfo {
  std::string name;                  ///< executable name, e.g. "fsi-modes"
  std::string summary;               ///< one line for --help
  std::string positional = "SCENE";  ///< name of the positional argument ("" for none)
  std::string positional_help = "scene file (TOML)";
  /// Input artefact options: option name without dashes → help ("mesh" → --mesh FILE).
  std::vector<std::pair<std::string, std::string>> inputs;
  bool has_output = true;  ///< -o/--output FILE
  bool has_validate = true;
  std::vector<std::pair<std::string, std::string>> flags;  ///< extra boolean flags → help
  std::string version_details;  ///< more lines for --version (what the build provides)
};

struct StageArgs {
  std::string positional;
  std::map<std::string, std::string> inputs;
  std::string output;
  bool validate = false;
  std::map<std::string, bool> flags;
  std::vector<std::string> overrides;  ///< --set KEY=VALUE, scene keys (stages taking a SCENE)
  Verbosity verbosity = Verbosity::normal;
};

int run_stage(int argc, char** argv, const StageInfo& info,
              const std::function<void(const StageArgs&)>& body);

/// What a scene-driven stage does: check the scene for itself, and run.
struct SceneStage {
  std::function<void(const io::Scene&)> validate;
  /// Inputs (by option name) and the output path are present when this is called.
  std::function<void(const io::Scene&, const std::map<std::string, std::string>& inputs,
                     const std::string& output)>
      run;
};

/// Logs the --set overrides a stage runs with (one line each).
void log_overrides(const std::string& stage, const std::vector<std::string>& overrides);

/// The common shape of fsi-mesh, fsi-modes, fsi-map, ...: load the scene, echo the resolved
/// parameters of this stage, then --validate or run (every --<input> and -o required).
int run_scene_stage(int argc, char** argv, const StageInfo& info, const SceneStage& stage);

}  // namespace hm::stages
