#pragma once
// fsi-simulate over MPI processes (`mpirun -np N fsi-simulate …`): a flow whose points are
// spread over the processes (ldd/exchange.hpp, parallel::FlowExchange), the
// output written once by process 0 from the points gathered there. A coupled structure is whole
// on every process, each advancing it alike on the loads summed over the processes
// (coupling/flexible_body.hpp). A stage run without mpirun
// (or by mpirun -np 1) never touches MPI and runs as it always has. The points written come
// from ldd::FlowSolver::output_points.
#include <memory>

#include "ldd/exchange.hpp"
#include "ldd/flow.hpp"

namespace hm::driver {

/// The processes the flow runs over; null for one process. InputError when started by mpirun
/// with several processes in a build without MPI (lib/parallel).
template <int D>
std::shared_ptr<ldd::PointExchange<D>> flow_processes();

/// Whether this process writes the run's output: the only one, or process 0 of several.
template <int D>
bool writes_output(const ldd::PointExchange<D>* processes) {
  return processes == nullptr || processes->rank() == 0;
}

/// Ends a distributed run from this process on `failure` (an exception perhaps no other process
/// sees): its message on stderr and every process aborted with the failure's exit code
/// (parallel::abort_run), so that none waits for ever in a collective call. Never returns.
[[noreturn]] void abort_processes(const std::exception& failure);

}  // namespace hm::driver
