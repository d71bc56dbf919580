#include <gtest/gtest.h>

#include "core/errors.hpp"
#include "geometry/cgal_checks.hpp"
#include "geometry/surface_checks.hpp"
#include "surfaces.hpp"

namespace hm::geometry {
namespace {

using hm::test::box_surface;
using hm::test::input_error_message;

const Eigen::Vector3d origin(0.1, 0.2, 0.3), size(0.5, 0.25, 0.125);
const double volume = 0.5 * 0.25 * 0.125;

TEST(SurfaceChecks, OutwardClosedBoxPassesUnchanged) {
  auto box = box_surface(origin, size);
  const auto before = box.cells;
  const auto report = check_closed_surface(box, "box");
  EXPECT_EQ(report.flipped_for_consistency, 0);
  EXPECT_EQ(report.flipped_outward, 0);
  EXPECT_EQ(report.components, 1);
  EXPECT_EQ(box.cells, before);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
  EXPECT_TRUE(cgal::is_outward_oriented(box));
}

TEST(SurfaceChecks, InwardBoxIsReversed) {
  auto box = box_surface(origin, size);
  reverse_cells(box);
  EXPECT_FALSE(cgal::is_outward_oriented(box));
  const auto report = check_closed_surface(box, "inward");
  EXPECT_EQ(report.flipped_outward, 12);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
  EXPECT_TRUE(cgal::is_outward_oriented(box));
}

TEST(SurfaceChecks, VerticesNoTriangleUsesAreIgnored) {
  // OBJ and PLY files may list vertices no face refers to; CGAL's orientation walk asserted on
  // them (found by fuzz_surface). An inward box behind an unused vertex, with one more at the end.
  auto box = box_surface(origin, size);
  reverse_cells(box);
  mesh::SurfaceMesh padded = box;
  padded.vertices.resize(box.vertices.rows() + 2, 3);
  padded.vertices.row(0) = Eigen::RowVector3d(9.0, 9.0, 9.0);
  padded.vertices.middleRows(1, box.vertices.rows()) = box.vertices;
  padded.vertices.row(box.vertices.rows() + 1) = Eigen::RowVector3d(-9.0, 0.0, 0.0);
  padded.cells = box.cells.array() + 1;
  const auto report = check_closed_surface(padded, "padded");
  EXPECT_EQ(report.flipped_outward, 12);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
  EXPECT_TRUE(cgal::is_outward_oriented(padded));
}

TEST(SurfaceChecks, OneFlippedTriangleIsMadeConsistent) {
  auto box = box_surface(origin, size);
  std::swap(box.cells(5, 1), box.cells(5, 2));
  const auto report = check_closed_surface(box, "one flipped");
  EXPECT_EQ(report.flipped_for_consistency, 1);
  EXPECT_EQ(report.flipped_outward, 0);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
}

TEST(SurfaceChecks, ConsistencyFollowsTheFirstTriangle) {
  // Triangle 0 (outward) is the odd one out: the other 11 are flipped to agree with it.
  auto box = box_surface(origin, size);
  reverse_cells(box);
  std::swap(box.cells(0, 1), box.cells(0, 2));
  const auto report = check_closed_surface(box, "mostly flipped");
  EXPECT_EQ(report.flipped_for_consistency, 11);
  EXPECT_EQ(report.flipped_outward, 0);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
}

TEST(SurfaceChecks, InconsistentInwardShellIsFixedThenReversed) {
  // Inward box with one outward triangle: 1 flip for consistency, then 12 to point outward.
  auto box = box_surface(origin, size);
  reverse_cells(box);
  std::swap(box.cells(5, 1), box.cells(5, 2));
  const auto report = check_closed_surface(box, "inward, one flipped");
  EXPECT_EQ(report.flipped_for_consistency, 1);
  EXPECT_EQ(report.flipped_outward, 12);
  EXPECT_NEAR(report.enclosed_volume, volume, 1e-15);
}

TEST(SurfaceChecks, HoleIsRejectedWithBorderEdgeCount) {
  auto box = box_surface(origin, size);
  mesh::SurfaceMesh open = box;
  open.cells.conservativeResize(11, 3);  // drop the last triangle: 3 border edges
  const auto message = input_error_message([&] { check_closed_surface(open, "holed.stl"); });
  EXPECT_NE(message.find("'holed.stl' is not closed"), std::string::npos) << message;
  EXPECT_NE(message.find("3 border edges"), std::string::npos) << message;
  // An edge of the removed triangle (0.1,0.2,0.425) (0.6,0.45,0.425) (0.1,0.45,0.425):
  EXPECT_NE(message.find("(0.1, 0.45, 0.425)"), std::string::npos) << message;
  EXPECT_EQ(count_border_edges(open), 3);
  EXPECT_EQ(count_border_edges(box), 0);
}

TEST(SurfaceChecks, SelfIntersectionIsRejectedWithTheFirstPair) {
  // Two overlapping closed boxes in one surface: each is fine alone, together they intersect.
  const auto a = box_surface({0, 0, 0}, {1, 1, 1});
  const auto b = box_surface({0.5, 0.25, 0.25}, {1, 0.5, 0.5});
  auto both = hm::test::combined(a, b);
  const auto pairs = cgal::self_intersecting_faces(both);
  // Box b crosses the face x = 1 of a (2 triangles) with its 4 side faces (8 triangles), and
  // its face x = 0.5 lies inside a; each crossing pair of triangles counts.
  EXPECT_GT(pairs.size(), 0u);
  for (const auto& [i, j] : pairs) EXPECT_TRUE((i < 12) != (j < 12)) << i << " " << j;
  const auto message = input_error_message([&] { check_closed_surface(both, "two_boxes.stl"); });
  EXPECT_NE(message.find("'two_boxes.stl' intersects itself"), std::string::npos) << message;
  EXPECT_NE(message.find(fmt::format("{} pairs", pairs.size())), std::string::npos) << message;
  EXPECT_NE(message.find("triangle "), std::string::npos) << message;
}

TEST(SurfaceChecks, DegenerateTriangleIsRejectedWithItsCoordinates) {
  auto box = box_surface(origin, size);
  box.vertices.conservativeResize(9, 3);
  box.vertices.row(8) = 0.5 * (box.vertices.row(0) + box.vertices.row(1));  // on edge 0-1
  box.cells.conservativeResize(13, 3);
  box.cells.row(12) << 0, 8, 1;  // collinear: zero area
  const auto message = input_error_message([&] { check_closed_surface(box, "degenerate.stl"); });
  EXPECT_NE(message.find("1 of 13 triangles are degenerate"), std::string::npos) << message;
  EXPECT_NE(message.find("triangle 12"), std::string::npos) << message;
  EXPECT_NE(message.find("(0.1, 0.2, 0.3625)"), std::string::npos) << message;
}

TEST(SurfaceChecks, EdgeOfThreeTrianglesIsNonManifold) {
  auto box = box_surface(origin, size);
  box.vertices.conservativeResize(9, 3);
  box.vertices.row(8) << 0.0, 0.0, 0.0;
  box.cells.conservativeResize(13, 3);
  box.cells.row(12) << 0, 1, 8;  // a fin on edge 0-1
  const auto message = input_error_message([&] { check_closed_surface(box, "fin.stl"); });
  // The fin's two free edges make the surface open; that is reported first.
  EXPECT_NE(message.find("not closed: 2 border edges"), std::string::npos) << message;
}

TEST(SurfaceChecks, UniformRefinementKeepsAreaVolumeAndOrientation) {
  const auto box = box_surface(origin, size);
  const auto fine = refine_uniformly(box, 0.1);
  // Longest edge: the face diagonal sqrt(0.5² + 0.25²) = 0.559 → 3 halvings → 0.0699.
  EXPECT_EQ(fine.cells.rows(), 12 * 64);
  EXPECT_NEAR(enclosed_volume(fine), volume, 1e-15);
  EXPECT_EQ(count_border_edges(fine), 0);
}

}  // namespace
}  // namespace hm::geometry
