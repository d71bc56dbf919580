#pragma once
// Small triangle surfaces for the geometry and mesh tests.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "mesh/types.hpp"

namespace hm::test {

/// Closed, outward-oriented box [origin, origin + size] as 8 vertices and 12 triangles.
inline mesh::SurfaceMesh box_surface(const Eigen::Vector3d& origin, const Eigen::Vector3d& size) {
  mesh::SurfaceMesh s;
  s.dim = 3;
  s.vertices.resize(8, 3);
  for (int x = 0; x < 2; ++x)
    for (int y = 0; y < 2; ++y)
      for (int z = 0; z < 2; ++z)
        s.vertices.row(4 * x + 2 * y + z) =
            (origin + Eigen::Vector3d(x * size.x(), y * size.y(), z * size.z())).transpose();
  const int quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
  s.cells.resize(12, 3);
  for (int q = 0; q < 6; ++q) {
    s.cells.row(2 * q) << quads[q][0], quads[q][1], quads[q][2];
    s.cells.row(2 * q + 1) << quads[q][0], quads[q][2], quads[q][3];
  }
  return s;
}

/// Two surfaces side by side in one mesh (vertices and cells appended).
inline mesh::SurfaceMesh combined(const mesh::SurfaceMesh& a, const mesh::SurfaceMesh& b) {
  mesh::SurfaceMesh s;
  s.dim = 3;
  s.vertices.resize(a.vertices.rows() + b.vertices.rows(), 3);
  s.vertices << a.vertices, b.vertices;
  s.cells.resize(a.cells.rows() + b.cells.rows(), 3);
  s.cells << a.cells, (b.cells.array() + a.vertices.rows()).matrix();
  return s;
}

/// A fresh directory for one test's files.
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  auto dir = std::filesystem::path(HM_BINARY_DIR) / "test-scratch" / info->test_suite_name() /
             info->name();
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs f and returns the InputError message; fails the test when f does not throw one.
template <typename F>
std::string input_error_message(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

}  // namespace hm::test
