#pragma once
// Checkpoints of fsi-simulate (hydromodal.checkpoint): the flow's state (ldd::FlowState), the
// flexible bodies' (coupling::BodyState) and the run so far (coupling::RunResult), written
// atomically at the checkpoint times and read by --restart. A restart refuses a checkpoint of
// other scene parameters (its provenance's parameters must equal the run's).
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "coupling/run.hpp"
#include "io/artefact.hpp"

namespace hm::driver {

template <int D>
struct Checkpoint {
  ldd::FlowState<D> flow;
  std::vector<coupling::BodyState> bodies;
  coupling::RunResult run;
};

/// Writes the checkpoint of the flow's state `flow` (FlowSolver::state), `bodies` and `run` to
/// `path` (atomically).
template <int D>
void write_checkpoint(const std::filesystem::path& path, const std::string& parameters,
                      const std::vector<io::InputRecord>& inputs, const ldd::FlowState<D>& flow,
                      std::span<const coupling::FlexibleBody<D>> bodies,
                      const coupling::RunResult& run);

/// Reads a checkpoint. InputError naming the file when its parameters differ from `parameters`
/// other than in time.end (another scene), its dimension is not D or it holds another number of
/// bodies.
template <int D>
Checkpoint<D> read_checkpoint(const std::filesystem::path& path, const std::string& parameters,
                              std::size_t bodies);

/// `<folder>/checkpoints/t_<time in ms, 6 decimals>.h5`.
std::filesystem::path checkpoint_path(const std::filesystem::path& folder, double time);

}  // namespace hm::driver
