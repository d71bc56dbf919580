#pragma once
// fsi-simulate: scene + mesh.h5 (+ mapped.h5) → results.h5 (hydromodal.results), with
// probes.csv and snapshots/ (flow_*.h5 + flow.xdmf for ParaView) next to it.
// Rigid walls are fixed or in prescribed motion; a [structure] in a flow scene is a flexible body
// (coupling/flexible_body.hpp) on the mapped modes.
#include <filesystem>

#include "io/scene.hpp"

namespace hm::driver {

/// Checks everything fsi-simulate needs from the scene without reading artefacts (--validate).
/// A scene without [fluid] is accepted only when it has a [structure] (structure-only runs come
/// with the modal coupling).
void validate_simulate_scene(const io::Scene& scene);

struct SimulateInputs {
  /// hydromodal.mesh with the walls. Empty: the walls are meshed from the scene (rigid-only
  /// scenes, which fsi-mesh refuses without a [structure]); their mesh keys then join the
  /// parameters (simulate_parameters) and wall files the provenance inputs.
  std::filesystem::path mesh;
  /// hydromodal.mapped_modes: the flexible body of a coupled scene ([fluid] and [structure]).
  std::filesystem::path mapped;
  /// hydromodal.modes: the modes of a structure-only run (a scene with no [fluid]).
  std::filesystem::path modes;
  /// hydromodal.checkpoint of this scene's run: continue from it instead of starting.
  std::filesystem::path restart;
};

/// The canonical parameters results.h5 records (and --if-stale compares): the fsi-simulate keys,
/// plus the [[wall]] mesh keys when the walls are meshed from the scene (no --mesh).
std::string simulate_parameters(const io::Scene& scene, bool walls_from_scene);

/// Runs the scene's flow to time.end and writes `output` atomically (provenance: scene, mesh or
/// wall files, mapped when given, motion tables), probes.csv and snapshots/ in the output's folder.
/// A run that diverges still writes results.h5 (status "diverged: ...", run_status "diverged", the
/// report in divergence_report), keeps its snapshots plus snapshots/diverged.xdmf of the failed
/// state, and then throws NumericalError (exit 3) with the report.
void run_simulate_stage(const io::Scene& scene, const SimulateInputs& inputs,
                        const std::filesystem::path& output);

}  // namespace hm::driver
