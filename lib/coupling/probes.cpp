#include "coupling/probes.hpp"

#include <array>

#include "core/errors.hpp"
#include "ldd/probes.hpp"

namespace hm::coupling {

template <int D>
std::vector<std::string> probe_columns(std::span<const Probe<D>> probes) {
  static constexpr std::array<const char*, 3> axes{".fx [N]", ".fy [N]", ".fz [N]"};
  std::vector<std::string> columns;
  for (const Probe<D>& p : probes) {
    switch (p.kind) {
      case ProbeKind::pressure:
        columns.push_back(p.name + ".p [Pa]");
        break;
      case ProbeKind::elevation:
        columns.push_back(p.name + ".eta [m]");
        break;
      case ProbeKind::front:
        columns.push_back(p.name + ".front [m]");
        break;
      case ProbeKind::force:
        for (int a = 0; a < D; ++a) columns.push_back(p.name + axes[static_cast<std::size_t>(a)]);
        break;
    }
  }
  return columns;
}

template <int D>
std::vector<double> evaluate_probes(const ldd::FlowSolver<D>& solver,
                                    std::span<const Probe<D>> probes) {
  const auto& points = solver.points();
  const auto& walls = solver.walls();
  const double dx = solver.dx();
  std::vector<double> row;
  for (const Probe<D>& p : probes) {
    switch (p.kind) {
      case ProbeKind::pressure:
        row.push_back(ldd::probe_pressure<D>(points, walls, p.position, p.radius, dx));
        break;
      case ProbeKind::elevation:
        row.push_back(ldd::probe_elevation<D>(points, p.position, dx));
        break;
      case ProbeKind::front:
        row.push_back(ldd::probe_front<D>(points, p.direction, p.band_low, p.band_high, dx));
        break;
      case ProbeKind::force: {
        HM_ASSERT(p.wall >= 0 && p.wall < static_cast<int>(walls.size()),
                  "probe '{}': wall index {} of {}", p.name, p.wall, walls.size());
        const auto loads = ldd::wall_pressure_loads<D>(
            points, walls[static_cast<std::size_t>(p.wall)], p.wall, dx);
        for (int a = 0; a < D; ++a) row.push_back(loads.total[a]);
        break;
      }
    }
  }
  return row;
}

template std::vector<std::string> probe_columns<2>(std::span<const Probe<2>>);
template std::vector<std::string> probe_columns<3>(std::span<const Probe<3>>);
template std::vector<double> evaluate_probes<2>(const ldd::FlowSolver<2>&,
                                                std::span<const Probe<2>>);
template std::vector<double> evaluate_probes<3>(const ldd::FlowSolver<3>&,
                                                std::span<const Probe<3>>);

}  // namespace hm::coupling
