#include "driver/flow_processes.hpp"

#include <cstdio>
#include <cstdlib>

#include <fmt/format.h>

#include "core/errors.hpp"
#ifdef HM_WITH_PARALLEL
#include "parallel/decomposition.hpp"
#include "parallel/flow_exchange.hpp"
#endif

namespace hm::driver {

template <int D>
std::shared_ptr<ldd::PointExchange<D>> flow_processes() {
#ifdef HM_WITH_PARALLEL
  if (!parallel::started_by_mpirun()) return nullptr;
  if (parallel::processes().count == 1) return nullptr;
  return std::make_shared<parallel::FlowExchange<D>>();
#else
  for (const char* variable : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* size = std::getenv(variable); size != nullptr && std::string(size) != "1")
      throw InputError(fmt::format(
          "fsi-simulate: started by mpirun with {} processes, but this hydromodal was built "
          "without MPI (install petsc-dev and libtrilinos-zoltan-dev and build again)",
          size));
  return nullptr;
#endif
}

void abort_processes(const std::exception& failure) {
  const auto* error = dynamic_cast<const Error*>(&failure);
  const auto code = error != nullptr ? error->code() : ExitCode::internal_error;
#ifdef HM_WITH_PARALLEL
  parallel::abort_run(failure.what(), static_cast<int>(code));
#else
  std::fprintf(stderr, "hydromodal: %s\n", failure.what());
  std::_Exit(static_cast<int>(code));
#endif
}

template std::shared_ptr<ldd::PointExchange<2>> flow_processes<2>();
template std::shared_ptr<ldd::PointExchange<3>> flow_processes<3>();

}  // namespace hm::driver
