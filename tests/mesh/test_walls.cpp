#include <gtest/gtest.h>
#include <Eigen/Geometry>
#include <omp.h>

#include "core/errors.hpp"
#include "geometry/surface_checks.hpp"
#include "geometry/surface_io.hpp"
#include "mesh/wall_mesher.hpp"
#include "surfaces.hpp"

namespace hm::mesh {
namespace {

const std::filesystem::path data_dir = std::filesystem::path(HM_SOURCE_DIR) / "data" / "geometry";

WallOptions walls(int dim, double size, std::vector<std::string> faces = {}) {
  WallOptions o;
  o.dim = dim;
  o.size = size;
  o.faces = std::move(faces);
  return o;
}

/// Σ normal × area (3-D) or Σ normal × length (2-D, normal ẑ×t), by the SurfaceMesh convention.
Eigen::Vector3d area_vector(const SurfaceMesh& s) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (Index c = 0; c < s.cells.rows(); ++c) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), q = p, r = p;
    p.head(s.dim) = s.vertices.row(s.cells(c, 0)).transpose();
    q.head(s.dim) = s.vertices.row(s.cells(c, 1)).transpose();
    if (s.dim == 3) r = s.vertices.row(s.cells(c, 2)).transpose();
    sum += s.dim == 2 ? Eigen::Vector3d(Eigen::Vector3d::UnitZ().cross(q - p))
                      : Eigen::Vector3d(0.5 * (q - p).cross(r - p));
  }
  return sum;
}

double measure(const SurfaceMesh& s) {
  double sum = 0.0;
  for (Index c = 0; c < s.cells.rows(); ++c) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), q = p, r = p;
    p.head(s.dim) = s.vertices.row(s.cells(c, 0)).transpose();
    q.head(s.dim) = s.vertices.row(s.cells(c, 1)).transpose();
    if (s.dim == 3) r = s.vertices.row(s.cells(c, 2)).transpose();
    sum += s.dim == 2 ? (q - p).norm() : 0.5 * (q - p).cross(r - p).norm();
  }
  return sum;
}

TEST(Walls, ClosedBoxTankPointsInward) {
  const Eigen::Vector3d o(0.0, 0.0, 0.0), s(1.0, 0.5, 0.6);
  const auto w = mesh_box_walls({o, s}, walls(3, 0.1));
  EXPECT_EQ(w.dim, 3);
  const double area = 2 * (s.x() * s.y() + s.y() * s.z() + s.z() * s.x());
  EXPECT_NEAR(measure(w), area, 1e-12 * area);
  EXPECT_EQ(geometry::count_border_edges(w), 0);  // faces share their edge vertices
  EXPECT_NEAR(geometry::enclosed_volume(w), -s.prod(), 1e-12 * s.prod());  // all normals inward
}

TEST(Walls, OpenTankOfChosenFaces) {
  const Eigen::Vector3d s(1.0, 0.5, 0.6);
  const auto w = mesh_box_walls({Eigen::Vector3d::Zero(), s}, walls(3, 0.1, {"zmin", "xmin"}));
  EXPECT_NEAR(measure(w), s.x() * s.y() + s.y() * s.z(), 1e-12);
  // Normal × area sums to +z·(floor) + x·(wall at x = 0): into the box.
  const Eigen::Vector3d a = area_vector(w);
  EXPECT_NEAR(a.x(), s.y() * s.z(), 1e-12);
  EXPECT_NEAR(a.y(), 0.0, 1e-12);
  EXPECT_NEAR(a.z(), s.x() * s.y(), 1e-12);
  const auto message = hm::test::input_error_message([&] {
    mesh_box_walls({Eigen::Vector3d::Zero(), s}, walls(3, 0.1, {"floor"}));
  });
  EXPECT_NE(
      message.find("wall face 'floor' does not exist; faces: [xmin, xmax, ymin, ymax, zmin, zmax]"),
      std::string::npos)
      << message;
}

// gmsh sets the process's OpenMP thread count to its General.NumThreads; a gmsh session must
// leave the count as it found it, or every solver after meshing runs on one thread.
TEST(Walls, MeshingKeepsTheOpenMpThreadCount) {
  omp_set_num_threads(3);
  mesh_rectangle_walls({{0.0, 0.0}, {1.0, 0.5}}, walls(2, 0.1, {"xmin", "ymin", "xmax"}));
  EXPECT_EQ(omp_get_max_threads(), 3);
}

TEST(Walls, RectangleTankSegmentsPointInward) {
  const auto w =
      mesh_rectangle_walls({{0.0, 0.0}, {1.6, 0.6}}, walls(2, 0.05, {"xmin", "ymin", "xmax"}));
  EXPECT_EQ(w.dim, 2);
  EXPECT_EQ(w.cells.cols(), 2);
  EXPECT_NEAR(measure(w), 0.6 + 1.6 + 0.6, 1e-13);
  const Eigen::Vector3d a = area_vector(w);  // xmin: +x 0.6, xmax: −x 0.6, ymin: +y 1.6
  EXPECT_NEAR(a.x(), 0.0, 1e-13);
  EXPECT_NEAR(a.y(), 1.6, 1e-13);
  double longest = 0.0;
  for (Index c = 0; c < w.cells.rows(); ++c)
    longest =
        std::max(longest, (w.vertices.row(w.cells(c, 1)) - w.vertices.row(w.cells(c, 0))).norm());
  EXPECT_LE(longest, 0.05 * (1 + 1e-9));
}

TEST(Walls, GeoScriptCurvesKeepTheirOrientation) {
  const auto w = mesh_wall_file(data_dir / "tank_walls_2d.geo", walls(2, 0.05));
  EXPECT_NEAR(measure(w), 0.6 + 1.0 + 0.6, 1e-13);
  const Eigen::Vector3d a = area_vector(w);  // curves drawn with the fluid on their left
  EXPECT_NEAR(a.x(), 0.0, 1e-13);
  EXPECT_NEAR(a.y(), 1.0, 1e-13);
  const auto bottom = mesh_wall_file(data_dir / "tank_walls_2d.geo", walls(2, 0.05, {"bottom"}));
  EXPECT_NEAR(measure(bottom), 1.0, 1e-13);
  const auto message = hm::test::input_error_message(
      [&] { mesh_wall_file(data_dir / "tank_walls_2d.geo", walls(2, 0.05, {"lid"})); });
  EXPECT_NE(
      message.find("wall group 'lid' is not a physical group of dimension 1; physical groups: "
                   "[bottom, sides]"),
      std::string::npos)
      << message;
}

TEST(Walls, ClosedStlTankIsOrientedInwardAndRefined) {
  const auto dir = hm::test::scratch_dir();
  geometry::write_stl_ascii(hm::test::box_surface({0, 0, 0}, {1.0, 0.5, 0.25}), dir / "tank.stl");
  const auto w = mesh_wall_file(dir / "tank.stl", walls(3, 0.1));
  EXPECT_NEAR(geometry::enclosed_volume(w), -0.125, 1e-15);
  double longest = 0.0;
  for (Index c = 0; c < w.cells.rows(); ++c)
    for (int k = 0; k < 3; ++k)
      longest = std::max(
          longest,
          (w.vertices.row(w.cells(c, k)) - w.vertices.row(w.cells(c, (k + 1) % 3))).norm());
  EXPECT_LE(longest, 0.1);
  auto flipped = walls(3, 0.1);
  flipped.flip_normals = true;
  EXPECT_NEAR(geometry::enclosed_volume(mesh_wall_file(dir / "tank.stl", flipped)), 0.125, 1e-15);
}

TEST(Walls, OpenStlKeepsItsOrientation) {
  const auto dir = hm::test::scratch_dir();
  auto tank = hm::test::box_surface({0, 0, 0}, {1.0, 0.5, 0.25});
  tank.cells.conservativeResize(10, 3);  // no lid (the last quad is the face z = 0.25): open
  geometry::write_stl_ascii(tank, dir / "open_tank.stl");
  const auto w =
      mesh_wall_file(dir / "open_tank.stl", walls(3, 1.2));  // longest edge 1.118: no split
  EXPECT_EQ(w.cells.rows(), 10);
  EXPECT_EQ(geometry::count_border_edges(w), 4);
  // As written (outward box without its lid): Σ n·A = −(lid's outward n·A) = (0, 0, −0.5).
  EXPECT_NEAR((area_vector(w) - Eigen::Vector3d(0, 0, -0.5)).norm(), 0.0, 1e-15);
}

}  // namespace
}  // namespace hm::mesh
