#include "mesh/quality.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>

#include <spdlog/spdlog.h>

namespace hm::mesh {
namespace {

Eigen::Vector3d corner(const StructureMesh& m, Index cell, int k) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(m.dim) = m.nodes.row(m.cells(cell, k)).transpose();
  return p;
}

double triangle_quality(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                        const Eigen::Vector3d& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area = 0.5 * (b - a).cross(c - a).norm();
  if (area <= 0.0) return 0.0;
  const double r_in = area / (0.5 * (la + lb + lc));
  const double r_circ = la * lb * lc / (4.0 * area);
  return 2.0 * r_in / r_circ;
}

double tet_quality(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                   const Eigen::Vector3d& p3) {
  const Eigen::Vector3d a = p1 - p0, b = p2 - p0, c = p3 - p0;
  const double six_v = std::abs(a.cross(b).dot(c));
  if (six_v <= 0.0) return 0.0;
  const double faces = 0.5 * ((a.cross(b)).norm() + (b.cross(c)).norm() + (c.cross(a)).norm() +
                              ((p2 - p1).cross(p3 - p1)).norm());
  const double r_in = 0.5 * six_v / faces;  // 3V / A
  const Eigen::Vector3d circ =
      a.squaredNorm() * b.cross(c) + b.squaredNorm() * c.cross(a) + c.squaredNorm() * a.cross(b);
  const double r_circ = circ.norm() / (2.0 * six_v);
  return 3.0 * r_in / r_circ;
}

}  // namespace

double cell_quality(const StructureMesh& mesh, Index cell) {
  if (mesh.dim == 2)
    return triangle_quality(corner(mesh, cell, 0), corner(mesh, cell, 1), corner(mesh, cell, 2));
  return tet_quality(corner(mesh, cell, 0), corner(mesh, cell, 1), corner(mesh, cell, 2),
                     corner(mesh, cell, 3));
}

double cell_measure(const StructureMesh& mesh, Index cell) {
  const Eigen::Vector3d a = corner(mesh, cell, 1) - corner(mesh, cell, 0);
  const Eigen::Vector3d b = corner(mesh, cell, 2) - corner(mesh, cell, 0);
  if (mesh.dim == 2) return 0.5 * std::abs(a.cross(b).z());
  const Eigen::Vector3d c = corner(mesh, cell, 3) - corner(mesh, cell, 0);
  return std::abs(a.cross(b).dot(c)) / 6.0;
}

MeshQuality assess_quality(const StructureMesh& mesh, double sliver_threshold) {
  MeshQuality q;
  q.dim = mesh.dim;
  q.cells = mesh.cells.rows();
  q.nodes = mesh.node_count();
  q.sliver_threshold = sliver_threshold;
  q.box = geometry::bounding_box(mesh.nodes);
  q.min_quality = std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (Index c = 0; c < q.cells; ++c) {
    const double quality = cell_quality(mesh, c);
    sum += quality;
    q.measure += cell_measure(mesh, c);
    if (quality < sliver_threshold) ++q.slivers;
    if (quality < q.min_quality) {
      q.min_quality = quality;
      q.worst_cell = c;
    }
  }
  if (q.cells == 0) q.min_quality = 0.0;
  q.mean_quality = q.cells > 0 ? sum / static_cast<double>(q.cells) : 0.0;
  return q;
}

void report_quality(const MeshQuality& q, std::string_view source) {
  spdlog::info("{}: {} nodes, {} cells, {} {:.6g} {}; radius-ratio quality min {:.3f} mean {:.3f}",
               source, q.nodes, q.cells, q.dim == 2 ? "area" : "volume", q.measure,
               q.dim == 2 ? "m²" : "m³", q.min_quality, q.mean_quality);
  geometry::report_extent(q.box, source);
  if (q.slivers > 0)
    spdlog::warn(
        "{}: {} of {} cells have quality below {} (slivers; worst cell {} with {:.3g}); "
        "refine or change the mesh size",
        source, q.slivers, q.cells, q.sliver_threshold, q.worst_cell, q.min_quality);
}

}  // namespace hm::mesh
