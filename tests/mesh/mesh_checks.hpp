#pragma once
// Invariants of quadratic structure meshes checked by the mesh tests.
#include <Eigen/Geometry>

#include "mesh/types.hpp"

namespace hm::test {

inline Eigen::Vector3d node3(const mesh::StructureMesh& m, mesh::Index n) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(m.dim) = m.nodes.row(n).transpose();
  return p;
}

/// Largest distance of a mid-edge node from the midpoint of its edge's corners (gmsh order).
inline double max_midnode_offset(const mesh::StructureMesh& m) {
  static const int tri6[3][3] = {{3, 0, 1}, {4, 1, 2}, {5, 2, 0}};
  static const int tet10[6][3] = {{4, 0, 1}, {5, 1, 2}, {6, 2, 0}, {7, 0, 3}, {8, 2, 3}, {9, 1, 3}};
  double worst = 0.0;
  for (mesh::Index c = 0; c < m.cells.rows(); ++c) {
    auto check = [&](const int(&e)[3]) {
      const Eigen::Vector3d mid = 0.5 * (node3(m, m.cells(c, e[1])) + node3(m, m.cells(c, e[2])));
      worst = std::max(worst, (node3(m, m.cells(c, e[0])) - mid).norm());
    };
    if (m.dim == 2)
      for (const auto& e : tri6) check(e);
    else
      for (const auto& e : tet10) check(e);
  }
  return worst;
}

/// Smallest signed corner Jacobian (2·area or 6·volume) over the cells.
inline double min_corner_jacobian(const mesh::StructureMesh& m) {
  double smallest = 1e300;
  for (mesh::Index c = 0; c < m.cells.rows(); ++c) {
    const Eigen::Vector3d a = node3(m, m.cells(c, 1)) - node3(m, m.cells(c, 0));
    const Eigen::Vector3d b = node3(m, m.cells(c, 2)) - node3(m, m.cells(c, 0));
    const double j = m.dim == 2 ? a.cross(b).z()
                                : a.cross(b).dot(node3(m, m.cells(c, 3)) - node3(m, m.cells(c, 0)));
    smallest = std::min(smallest, j);
  }
  return smallest;
}

/// Outward normal × measure of a facet (length in 2-D, area in 3-D), from its corners.
inline Eigen::Vector3d facet_area_vector(const mesh::StructureMesh& m, mesh::Index f) {
  const Eigen::Vector3d a = node3(m, m.facets(f, 0)), b = node3(m, m.facets(f, 1));
  if (m.dim == 2) return (b - a).cross(Eigen::Vector3d::UnitZ());  // structure on the left of a→b
  return 0.5 * (b - a).cross(node3(m, m.facets(f, 2)) - a);
}

inline Eigen::Vector3d facet_centroid(const mesh::StructureMesh& m, mesh::Index f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < m.dim; ++k) c += node3(m, m.facets(f, k));
  return c / m.dim;
}

/// Σ_facets (x·n) |facet| / dim: the enclosed area/volume by the divergence theorem, which
/// equals the mesh's measure only when the boundary is closed and every facet points outward.
inline double divergence_measure(const mesh::StructureMesh& m) {
  double sum = 0.0;
  for (mesh::Index f = 0; f < m.facets.rows(); ++f)
    sum += facet_centroid(m, f).dot(facet_area_vector(m, f));
  return sum / m.dim;
}

inline double facet_measure(const mesh::StructureMesh& m, const std::vector<mesh::Index>& facets) {
  double sum = 0.0;
  for (mesh::Index f : facets) sum += facet_area_vector(m, f).norm();
  return sum;
}

}  // namespace hm::test
