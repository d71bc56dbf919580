#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "geometry/surface_checks.hpp"
#include "mesh/boundary.hpp"
#include "mesh/quality.hpp"
#include "mesh/structure_mesher.hpp"
#include "mesh_checks.hpp"
#include "surfaces.hpp"

namespace hm::mesh {
namespace {

/// One straight-sided tet10 on the given corners, mid-edge nodes at the midpoints.
StructureMesh single_tet(const std::array<Eigen::Vector3d, 4>& corner) {
  StructureMesh m;
  m.dim = 3;
  m.nodes.resize(10, 3);
  for (int k = 0; k < 4; ++k) m.nodes.row(k) = corner[static_cast<std::size_t>(k)].transpose();
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
  for (int e = 0; e < 6; ++e)
    m.nodes.row(4 + e) = 0.5 * (m.nodes.row(edges[e][0]) + m.nodes.row(edges[e][1]));
  m.cells.resize(1, 10);
  for (int k = 0; k < 10; ++k) m.cells(0, k) = k;
  return m;
}

TEST(Quality, RegularTetIsOneFlatTetIsNearZero) {
  const auto regular = single_tet({Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(1, -1, -1),
                                   Eigen::Vector3d(-1, 1, -1), Eigen::Vector3d(-1, -1, 1)});
  EXPECT_NEAR(cell_quality(regular, 0), 1.0, 1e-14);
  // A sliver: four corners of a square, one lifted by 1e-3 of the edge.
  const auto sliver = single_tet({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                  Eigen::Vector3d(1, 1, 1e-3), Eigen::Vector3d(0, 1, 0)});
  const auto q = assess_quality(sliver, 0.1);
  EXPECT_LT(q.min_quality, 0.01);
  EXPECT_EQ(q.slivers, 1);
  EXPECT_NEAR(q.measure, 1e-3 / 6.0 * 1.0, 1e-18);
}

TEST(Boundary, NegativeTetIsReorderedAndItsFacesPointOut) {
  auto m = single_tet({Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(1, 0, 0),
                       Eigen::Vector3d(0, 0, 1)});  // left-handed
  EXPECT_LT(hm::test::min_corner_jacobian(m), 0.0);
  EXPECT_EQ(orient_cells_positively(m), 1);
  EXPECT_GT(hm::test::min_corner_jacobian(m), 0.0);
  EXPECT_EQ(hm::test::max_midnode_offset(m), 0.0);  // mid-edge nodes followed their corners
  build_boundary_facets(m);
  ASSERT_EQ(m.facets.rows(), 4);
  EXPECT_NEAR(hm::test::divergence_measure(m), 1.0 / 6.0, 1e-16);
  // Facet mid-edge nodes sit at the midpoints of the facet's corner edges (tri6 order).
  for (Index f = 0; f < 4; ++f)
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d mid =
          0.5 * (hm::test::node3(m, m.facets(f, e)) + hm::test::node3(m, m.facets(f, (e + 1) % 3)));
      EXPECT_EQ((hm::test::node3(m, m.facets(f, 3 + e)) - mid).norm(), 0.0);
    }
}

double surface_area(const SurfaceMesh& s) {
  double a = 0.0;
  for (Index c = 0; c < s.cells.rows(); ++c) {
    const Eigen::Vector3d p = s.vertices.row(s.cells(c, 0)).transpose();
    const Eigen::Vector3d q = s.vertices.row(s.cells(c, 1)).transpose();
    const Eigen::Vector3d r = s.vertices.row(s.cells(c, 2)).transpose();
    a += 0.5 * (q - p).cross(r - p).norm();
  }
  return a;
}

TEST(Boundary, ExtractedSurfaceKeepsAreaOrientationAndNodeLinks) {
  MeshOptions o;
  o.dim = 3;
  o.size = 0.01;
  const Eigen::Vector3d s(0.05, 0.02, 0.03);
  const auto m = mesh_box({Eigen::Vector3d::Zero(), s}, o);
  const double area = 2 * (s.x() * s.y() + s.y() * s.z() + s.z() * s.x());
  for (auto split : {SurfaceSplit::corners, SurfaceSplit::refined}) {
    const auto b = extract_boundary_surface(m, split);
    EXPECT_EQ(b.surface.cells.rows(), m.facets.rows() * (split == SurfaceSplit::corners ? 1 : 4));
    EXPECT_NEAR(surface_area(b.surface), area, 1e-12 * area);
    EXPECT_NEAR(geometry::enclosed_volume(b.surface), s.prod(), 1e-12 * s.prod());  // outward
    for (std::size_t v = 0; v < b.volume_node.size(); ++v)
      EXPECT_EQ(b.surface.vertices.row(static_cast<Index>(v)), m.nodes.row(b.volume_node[v]));
  }
  const auto zmax = extract_boundary_surface(m, SurfaceSplit::refined, "zmax");
  EXPECT_NEAR(surface_area(zmax.surface), s.x() * s.y(), 1e-12);
  const auto message = hm::test::input_error_message(
      [&] { extract_boundary_surface(m, SurfaceSplit::corners, "top"); });
  EXPECT_NE(message.find("boundary group 'top' does not exist"), std::string::npos) << message;
  EXPECT_NE(message.find("[xmax, xmin, ymax, ymin, zmax, zmin]"), std::string::npos) << message;
}

TEST(Boundary, Extracted2dSegmentsHaveTheStructureOnTheirRight) {
  MeshOptions o;
  o.dim = 2;
  o.size = 0.002;
  const auto m = mesh_rectangle({{0.0, 0.0}, {0.005, 0.079}}, o);
  for (auto split : {SurfaceSplit::corners, SurfaceSplit::refined}) {
    const auto b = extract_boundary_surface(m, split);
    // Shoelace over the segments: −area when traversed clockwise (left normals point out).
    double twice_area = 0.0, length = 0.0;
    for (Index c = 0; c < b.surface.cells.rows(); ++c) {
      const Eigen::Vector2d p = b.surface.vertices.row(b.surface.cells(c, 0)).transpose();
      const Eigen::Vector2d q = b.surface.vertices.row(b.surface.cells(c, 1)).transpose();
      twice_area += p.x() * q.y() - p.y() * q.x();
      length += (q - p).norm();
    }
    EXPECT_NEAR(0.5 * twice_area, -0.005 * 0.079, 1e-12 * 0.005 * 0.079);
    EXPECT_NEAR(length, 2 * (0.005 + 0.079), 1e-14);
  }
}

}  // namespace
}  // namespace hm::mesh
