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

template <int D>
ldd::PointSet<D> gather_points(const ldd::FlowSolver<D>& flow) {
#ifdef HM_WITH_PARALLEL
  // velocity, pressure, kind, type, wall normal, host (body, element, barycentric)
  constexpr int width = 3 * D + 5;
  const auto& p = flow.points();
  parallel::PointBlock<D> mine{.width = width};
  std::vector<double> f(width);
  for (ldd::Index i = 0; i < flow.owned(); ++i) {
    double* v = f.data();
    v = std::copy_n(p.velocity[i].data(), D, v);
    *v++ = p.pressure[i];
    *v++ = static_cast<double>(p.kind[i]);
    *v++ = static_cast<double>(p.type[i]);
    v = std::copy_n(p.wall_normal[i].data(), D, v);
    *v++ = p.host[i].body;
    *v++ = static_cast<double>(p.host[i].element);
    std::copy_n(p.host[i].barycentric.data(), D, v);
    mine.add(p.position[i], flow.ids()[static_cast<std::size_t>(i)], f.data());
  }
  const auto all = parallel::gather_on_first(mine);
  ldd::PointSet<D> points;
  for (std::size_t k = 0; k < all.size(); ++k) {
    const double* v = &all.fields[k * width];
    const ldd::Vec<D> velocity = Eigen::Map<const ldd::Vec<D>>(v);
    const auto kind = static_cast<ldd::PointKind>(v[D + 1]);
    ldd::WallHost<D> host;
    host.body = static_cast<int>(v[2 * D + 3]);
    host.element = static_cast<ldd::Index>(v[2 * D + 4]);
    host.barycentric = Eigen::Map<const ldd::Vec<D>>(v + 2 * D + 5);
    const ldd::Index i =
        kind == ldd::PointKind::fluid
            ? points.add_fluid(all.position[k], velocity)
            : points.add_wall_node(all.position[k], Eigen::Map<const ldd::Vec<D>>(v + D + 3), host);
    points.velocity[i] = velocity;
    points.pressure[i] = v[D];
    points.type[i] = static_cast<ldd::PointType>(v[D + 2]);
  }
  return points;
#else
  (void)flow;
  throw std::logic_error("gather_points: a build without MPI has no distributed flows");
#endif
}

template std::shared_ptr<ldd::PointExchange<2>> flow_processes<2>(const DistributedRequest&);
template std::shared_ptr<ldd::PointExchange<3>> flow_processes<3>(const DistributedRequest&);
template ldd::PointSet<2> gather_points<2>(const ldd::FlowSolver<2>&);
template ldd::PointSet<3> gather_points<3>(const ldd::FlowSolver<3>&);

}  // namespace hm::driver
