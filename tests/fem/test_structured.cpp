// Structured tri6/tet10 meshes: counts, conformity, facet orientation and groups.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "mesh/structured.hpp"

namespace hm::mesh {
namespace {

Eigen::Vector3d point(const StructureMesh& m, Index node) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(m.dim) = m.nodes.row(node).transpose();
  return p;
}

TEST(StructuredRectangle, CountsOrientationAndMidNodes) {
  const StructureMesh m = structured_rectangle(2.0, 1.0, 4, 3, {0.5, -1.0});
  EXPECT_EQ(m.dim, 2);
  EXPECT_EQ(m.node_count(), 9 * 7);
  EXPECT_EQ(m.cells.rows(), 2 * 4 * 3);
  double area = 0.0;
  for (Index c = 0; c < m.cells.rows(); ++c) {
    const Eigen::Vector3d a = point(m, m.cells(c, 0)), b = point(m, m.cells(c, 1)),
                          d = point(m, m.cells(c, 2));
    const double twice_area = (b - a).cross(d - a).z();
    EXPECT_GT(twice_area, 0.0) << "cell " << c;
    area += 0.5 * twice_area;
    // mid-edge nodes in gmsh order 3:e01 4:e12 5:e20
    EXPECT_LT((point(m, m.cells(c, 3)) - 0.5 * (a + b)).norm(), 1e-14);
    EXPECT_LT((point(m, m.cells(c, 4)) - 0.5 * (b + d)).norm(), 1e-14);
    EXPECT_LT((point(m, m.cells(c, 5)) - 0.5 * (d + a)).norm(), 1e-14);
  }
  EXPECT_NEAR(area, 2.0, 1e-13);
  EXPECT_DOUBLE_EQ(m.nodes.col(0).minCoeff(), 0.5);
  EXPECT_DOUBLE_EQ(m.nodes.col(1).maxCoeff(), 0.0);
}

TEST(StructuredRectangle, BoundaryGroupsAndOutwardFacets) {
  const StructureMesh m = structured_rectangle(2.0, 1.0, 4, 3);
  EXPECT_EQ(m.facets.rows(), 2 * (4 + 3));
  EXPECT_EQ(m.node_groups.at("xmin").size(), 7u);
  EXPECT_EQ(m.node_groups.at("ymax").size(), 9u);
  const std::map<std::string, Eigen::Vector3d> outward{{"xmin", -Eigen::Vector3d::UnitX()},
                                                       {"xmax", Eigen::Vector3d::UnitX()},
                                                       {"ymin", -Eigen::Vector3d::UnitY()},
                                                       {"ymax", Eigen::Vector3d::UnitY()}};
  for (const auto& [side, normal] : outward) {
    double length = 0.0;
    for (Index f : m.facet_groups.at(side)) {
      const Eigen::Vector3d a = point(m, m.facets(f, 0)), b = point(m, m.facets(f, 1));
      const Eigen::Vector3d t = b - a;
      EXPECT_GT(Eigen::Vector3d(t.y(), -t.x(), 0).dot(normal), 0.0) << side;
      EXPECT_LT((point(m, m.facets(f, 2)) - 0.5 * (a + b)).norm(), 1e-14);
      length += t.norm();
      for (int k = 0; k < 3; ++k)
        EXPECT_TRUE(std::binary_search(m.node_groups.at(side).begin(), m.node_groups.at(side).end(),
                                       m.facets(f, k)));
    }
    EXPECT_NEAR(length, side[0] == 'x' ? 1.0 : 2.0, 1e-14) << side;
  }
}

TEST(StructuredBox, ConformingPositiveTetsWithOutwardFacets) {
  const StructureMesh m = structured_box(1.0, 0.5, 0.25, 3, 2, 2);
  EXPECT_EQ(m.node_count(), 7 * 5 * 5);
  EXPECT_EQ(m.cells.rows(), 6 * 12);
  // Each tet face (as a sorted triple of corners) is shared by two tets inside and belongs to
  // one tet on the boundary; the boundary faces are exactly the facets.
  std::map<std::array<Index, 3>, int> face_count;
  double volume = 0.0;
  for (Index c = 0; c < m.cells.rows(); ++c) {
    const Eigen::Vector3d x0 = point(m, m.cells(c, 0));
    const double v6 = (point(m, m.cells(c, 1)) - x0)
                          .cross(point(m, m.cells(c, 2)) - x0)
                          .dot(point(m, m.cells(c, 3)) - x0);
    EXPECT_GT(v6, 0.0) << "cell " << c;
    volume += v6 / 6.0;
    for (const auto& f : {std::array<int, 3>{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}) {
      std::array<Index, 3> key{m.cells(c, f[0]), m.cells(c, f[1]), m.cells(c, f[2])};
      std::sort(key.begin(), key.end());
      ++face_count[key];
    }
    // tet10 mid-edge nodes, gmsh order 4:e01 5:e12 6:e20 7:e03 8:e23 9:e13
    const std::array<std::array<int, 2>, 6> edges{{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};
    for (int e = 0; e < 6; ++e)
      EXPECT_LT((point(m, m.cells(c, 4 + e)) -
                 0.5 * (point(m, m.cells(c, edges[e][0])) + point(m, m.cells(c, edges[e][1]))))
                    .norm(),
                1e-14);
  }
  EXPECT_NEAR(volume, 0.125, 1e-14);
  std::set<std::array<Index, 3>> boundary;
  for (const auto& [key, count] : face_count) {
    EXPECT_LE(count, 2);
    if (count == 1) boundary.insert(key);
  }
  EXPECT_EQ(static_cast<Index>(boundary.size()), m.facets.rows());
  const Eigen::Vector3d centre(0.5, 0.25, 0.125);
  double area = 0.0;
  for (Index f = 0; f < m.facets.rows(); ++f) {
    std::array<Index, 3> key{m.facets(f, 0), m.facets(f, 1), m.facets(f, 2)};
    std::sort(key.begin(), key.end());
    EXPECT_TRUE(boundary.count(key)) << "facet " << f << " is not a boundary face of a cell";
    const Eigen::Vector3d a = point(m, m.facets(f, 0));
    const Eigen::Vector3d n = (point(m, m.facets(f, 1)) - a).cross(point(m, m.facets(f, 2)) - a);
    EXPECT_GT(n.dot(a - centre), 0.0) << "facet " << f << " points inwards";
    area += 0.5 * n.norm();
  }
  EXPECT_NEAR(area, 2 * (0.5 + 0.25 + 0.125), 1e-13);
}

TEST(StructuredBox, SideGroupsHoldTheirNodesAndFacets) {
  const StructureMesh m = structured_box(1.0, 0.5, 0.25, 3, 2, 2);
  const std::array<std::string, 6> names{"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};
  const Eigen::Vector3d hi(1.0, 0.5, 0.25);
  for (int s = 0; s < 6; ++s) {
    const int axis = s / 2;
    const double plane = s % 2 ? hi[axis] : 0.0;
    const auto& nodes = m.node_groups.at(names[s]);
    const Index expected = m.node_count() / (axis == 0 ? 7 : 5);
    EXPECT_EQ(static_cast<Index>(nodes.size()), expected) << names[s];
    for (Index n : nodes) EXPECT_DOUBLE_EQ(m.nodes(n, axis), plane);
    EXPECT_TRUE(std::is_sorted(nodes.begin(), nodes.end()));
    for (Index f : m.facet_groups.at(names[s]))
      for (int k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(m.nodes(m.facets(f, k), axis), plane);
  }
}

TEST(StructuredMesh, RejectsEmptyExtents) {
  try {
    structured_box(1.0, 0.0, 1.0, 1, 1, 1);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ly = 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(structured_rectangle(1.0, 1.0, 0, 1), InputError);
}

}  // namespace
}  // namespace hm::mesh
