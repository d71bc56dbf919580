#include "coupling/probes.hpp"

#include <Eigen/Geometry>

#include <array>
#include <cmath>

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

namespace {

/// Orthonormal frame of wall element e (columns: tangent(s), then the normal into the fluid).
template <int D>
ldd::Mat<D> element_frame(const ldd::WallMesh<D>& wall, ldd::Index e) {
  const auto& c = wall.element(e);
  const auto& x = wall.vertices();
  ldd::Vec<D> centre = ldd::Vec<D>::Constant(1.0 / D);
  const ldd::Vec<D> normal = wall.normal_at(e, centre);
  const ldd::Vec<D> t1 = (x[c[1]] - x[c[0]]).normalized();
  ldd::Mat<D> frame;
  frame.col(0) = t1;
  if constexpr (D == 3) frame.col(1) = normal.cross(t1);
  frame.col(D - 1) = normal;
  return frame;
}

}  // namespace

template <int D>
void attach_probe(Probe<D>& probe, const ldd::WallMesh<D>& wall, int index) {
  const auto c = wall.closest(probe.position);
  probe.attached = index;
  probe.element = c.element;
  probe.barycentric = c.barycentric;
  probe.local = element_frame<D>(wall, c.element).transpose() * (probe.position - c.point);
}

template <int D>
ldd::Vec<D> probe_position(const Probe<D>& probe, std::span<const ldd::WallMesh<D>> walls) {
  if (probe.attached < 0) return probe.position;
  const auto& wall = walls[static_cast<std::size_t>(probe.attached)];
  return wall.point_at(probe.element, probe.barycentric) +
         element_frame<D>(wall, probe.element) * probe.local;
}

template <int D>
std::vector<double> evaluate_probes(const ldd::FlowSolver<D>& solver,
                                    std::span<const Probe<D>> probes) {
  return evaluate_probes<D>(solver.points(), solver.walls(), solver.dx(), probes);
}

template <int D>
std::vector<double> evaluate_probes(const ldd::PointSet<D>& points,
                                    std::span<const ldd::WallMesh<D>> walls, double dx,
                                    std::span<const Probe<D>> probes) {
  constexpr double missing = probe_missing_value;
  std::vector<double> row;
  for (const Probe<D>& p : probes) {
    bool wet = false;
    switch (p.kind) {
      case ProbeKind::pressure: {
        const double v =
            ldd::probe_pressure<D>(points, walls, probe_position<D>(p, walls), p.radius, dx, &wet);
        row.push_back(wet ? v : missing);
        break;
      }
      case ProbeKind::elevation: {
        const double v = ldd::probe_elevation<D>(points, probe_position<D>(p, walls), dx, &wet);
        row.push_back(wet ? v : missing);
        break;
      }
      case ProbeKind::front: {
        const double v =
            ldd::probe_front<D>(points, p.direction, p.band_low, p.band_high, dx, &wet);
        row.push_back(wet ? v : missing);
        break;
      }
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

template <int D>
std::vector<std::string> probes_without_fluid(std::span<const Probe<D>> probes,
                                              std::span<const std::vector<double>> rows) {
  std::vector<std::string> names;
  std::size_t column = 0;
  for (const Probe<D>& p : probes) {
    const std::size_t width = p.kind == ProbeKind::force ? D : 1;
    bool saw_fluid = false;
    for (const auto& row : rows)
      for (std::size_t c = column; c < column + width && c < row.size(); ++c)
        saw_fluid = saw_fluid || (p.kind == ProbeKind::force ? row[c] != 0.0 : !std::isnan(row[c]));
    if (!saw_fluid) names.push_back(p.name);
    column += width;
  }
  return names;
}

template void attach_probe<2>(Probe<2>&, const ldd::WallMesh<2>&, int);
template void attach_probe<3>(Probe<3>&, const ldd::WallMesh<3>&, int);
template ldd::Vec<2> probe_position<2>(const Probe<2>&, std::span<const ldd::WallMesh<2>>);
template ldd::Vec<3> probe_position<3>(const Probe<3>&, std::span<const ldd::WallMesh<3>>);
template std::vector<std::string> probe_columns<2>(std::span<const Probe<2>>);
template std::vector<std::string> probe_columns<3>(std::span<const Probe<3>>);
template std::vector<double> evaluate_probes<2>(const ldd::FlowSolver<2>&,
                                                std::span<const Probe<2>>);
template std::vector<double> evaluate_probes<3>(const ldd::FlowSolver<3>&,
                                                std::span<const Probe<3>>);
template std::vector<double> evaluate_probes<2>(const ldd::PointSet<2>&,
                                                std::span<const ldd::WallMesh<2>>, double,
                                                std::span<const Probe<2>>);
template std::vector<double> evaluate_probes<3>(const ldd::PointSet<3>&,
                                                std::span<const ldd::WallMesh<3>>, double,
                                                std::span<const Probe<3>>);
template std::vector<std::string> probes_without_fluid<2>(std::span<const Probe<2>>,
                                                          std::span<const std::vector<double>>);
template std::vector<std::string> probes_without_fluid<3>(std::span<const Probe<3>>,
                                                          std::span<const std::vector<double>>);

}  // namespace hm::coupling
