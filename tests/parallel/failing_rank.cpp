// A run in which one process fails while the others wait for it in a collective call: run by
// ctest as `mpirun -np N failing_rank <how>` (N = 2, 4) under a timeout, expecting the whole run
// to end with a non-zero exit instead of hanging. <how>: "throws" — an exception, handled by
// parallel::abort_run (its message names the process); "killed" — the process is killed
// (SIGKILL), which OpenMPI's runtime notices and ends the run for.
#include <mpi.h>

#include <csignal>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "parallel/decomposition.hpp"

int main(int argc, char** argv) {
  const auto p = hm::parallel::processes();
  const std::string how = argc > 1 ? argv[1] : "throws";
  try {
    if (p.rank == p.count - 1) {
      if (how == "killed") std::raise(SIGKILL);
      throw std::runtime_error("a PPE that did not converge (a test)");
    }
    MPI_Barrier(MPI_COMM_WORLD);  // the others wait here for the failed one, forever
    std::printf("process %d passed the barrier: the failure did not end the run\n", p.rank);
  } catch (const std::exception& e) {
    hm::parallel::abort_run(e.what(), 3);
  }
  return 0;
}
