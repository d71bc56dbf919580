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

namespace {

void refuse(bool what, const char* text, int processes) {
  if (what)
    throw InputError(fmt::format(
        "fsi-simulate: {} does not run over several processes yet (started by mpirun with {}): "
        "run it as one process",
        text, processes));
}

}  // namespace

template <int D>
std::shared_ptr<ldd::PointExchange<D>> flow_processes(const DistributedRequest& request) {
#ifdef HM_WITH_PARALLEL
  if (!parallel::started_by_mpirun()) return nullptr;
  const int count = parallel::processes().count;
  if (count == 1) return nullptr;
  refuse(request.structure, "a flow coupled with a [structure]", count);
  return std::make_shared<parallel::FlowExchange<D>>();
#else
  (void)request;
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

template std::shared_ptr<ldd::PointExchange<2>> flow_processes<2>(const DistributedRequest&);
template std::shared_ptr<ldd::PointExchange<3>> flow_processes<3>(const DistributedRequest&);

}  // namespace hm::driver
