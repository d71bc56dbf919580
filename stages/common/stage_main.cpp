#include "stage_main.hpp"

#include <CLI/CLI.hpp>

#include <iostream>

#include "core/errors.hpp"
#include "core/version.hpp"
#include "io/artefact.hpp"
#include "io/atomic_file.hpp"
#include "io/scene.hpp"

namespace hm::stages {

namespace {
constexpr const char* exit_code_text =
    "Exit codes: 0 ok, 1 usage error, 2 invalid input (scene, artefact or geometry), "
    "3 numerical failure (no convergence, divergence), 4 internal error (please report).";
}

int run_stage(int argc, char** argv, const StageInfo& info,
              const std::function<void(const StageArgs&)>& body) {
  CLI::App app{info.summary, info.name};
  app.footer(exit_code_text);
  StageArgs args;
  bool quiet = false, verbose = false, print_reference = false, version = false;
  if (!info.positional.empty())
    app.add_option(info.positional, args.positional, info.positional_help);
  for (const auto& [name, help] : info.inputs)
    app.add_option("--" + name, args.inputs[name], help)->type_name("FILE");
  if (info.has_output)
    app.add_option("-o,--output", args.output, "output artefact")->type_name("FILE");
  if (info.has_validate)
    app.add_flag("--validate", args.validate,
                 "check the scene for this stage and exit; runs nothing");
  for (const auto& [name, help] : info.flags) app.add_flag("--" + name, args.flags[name], help);
  if (info.positional == "SCENE")
    app.add_option("--set", args.overrides,
                   "override a scene key, e.g. --set fluid.dx=0.005 --set wall[0].mesh_size=0.02 "
                   "(repeatable; checked like the file; the artefact records the values used)")
        ->type_name("KEY=VALUE");
  app.add_flag("--print-config-reference", print_reference,
               "print the reference of every scene key (Markdown) and exit");
  app.add_flag("-q,--quiet", quiet, "only warnings and errors");
  app.add_flag("-v,--verbose", verbose, "debug output");
  app.add_flag("--version", version, "print the tool version and exit");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : static_cast<int>(ExitCode::usage);
  }
  if (version) {
    std::cout << info.name << " " << tool_version() << "\n";
    if (!info.version_details.empty()) std::cout << info.version_details << "\n";
    return 0;
  }
  if (print_reference) {
    std::cout << io::scene_reference_markdown();
    return 0;
  }
  args.verbosity = quiet ? Verbosity::quiet : verbose ? Verbosity::verbose : Verbosity::normal;
  configure_logging(args.verbosity);
  io::install_interrupt_cleanup();
  try {
    if (!info.positional.empty() && args.positional.empty())
      throw UsageError(
          fmt::format("missing the {} argument; see {} --help", info.positional, info.name));
    body(args);
    return 0;
  } catch (const Error& e) {
    spdlog::error("{}", e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    spdlog::error("internal error (please report): {}", e.what());
    return static_cast<int>(ExitCode::internal_error);
  }
}

void log_overrides(const std::string& stage, const std::vector<std::string>& overrides) {
  for (const auto& setting : overrides) spdlog::info("{}: --set {}", stage, setting);
}

int run_scene_stage(int argc, char** argv, const StageInfo& scene_info, const SceneStage& stage) {
  StageInfo info = scene_info;
  info.flags.emplace_back("if-stale",
                          "run only if the output is missing or stale: written by another tool "
                          "version, with other scene parameters, or from inputs whose content "
                          "changed (content hashes decide, not timestamps)");
  return run_stage(argc, argv, info, [&](const StageArgs& args) {
    const io::Scene scene = io::Scene::load(args.positional, args.overrides);
    log_overrides(info.name, args.overrides);
    spdlog::info("{}: resolved parameters of {}:\n{}", info.name, args.positional,
                 scene.parameters_for(info.name));
    if (args.validate) {
      stage.validate(scene);
      spdlog::info("{}: {} is valid for this stage", info.name, args.positional);
      return;
    }
    if (args.output.empty()) throw UsageError(info.name + ": -o/--output FILE is required");
    for (const auto& [name, path] : args.inputs)
      if (path.empty()) throw UsageError(fmt::format("{}: --{} FILE is required", info.name, name));
    if (args.flags.at("if-stale")) {
      const std::string reason =
          io::staleness(args.output, info.name, scene.parameters_for(info.name), args.inputs);
      if (reason.empty()) {
        spdlog::info("{}: {} is up to date", info.name, args.output);
        return;
      }
      spdlog::info("{}: (re)making {}: {}", info.name, args.output, reason);
    }
    stage.run(scene, args.inputs, args.output);
  });
}

}  // namespace hm::stages
