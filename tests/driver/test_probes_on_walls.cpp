// Pressure probes on a wall's face (issue: a probe placed exactly on an STL obstacle's face read
// 0 Pa for a whole run). A dam break hits an obstacle given as a file wall (2-D: a .geo curve
// loop; 3-D: an STL whose face coordinate is not exact in single precision); probes on the
// obstacle's face and on the tank's wall at x = 0 (a box/rectangle wall) must read what a probe
// 0.1 dx inside the fluid reads, within 5 % of its peak. And the refusals: a probe inside the
// obstacle, on a thin wall — each naming the probe, its position and the fluid side.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include "../common/replaced.hpp"
#include "driver/flow_setup.hpp"
#include "ldd/flow.hpp"

using hm::test::replaced;

namespace hm::driver {
namespace {

namespace fs = std::filesystem;

const fs::path folder = fs::path(HM_BINARY_DIR) / "tests" / "driver" / "probes_on_walls";

// 2-D: tank 0.4 × 0.3 m, a column 0.1 × 0.1 m against x = 0, the obstacle [0.2545, 0.2845] ×
// [0, 0.04] m standing on the floor (a closed loop, clockwise: normals out of it).
constexpr double face_2d = 0.2545, dx_2d = 0.0025;

const std::string obstacle_geo = R"(// the obstacle, clockwise: fluid outside
Point(1) = {0.2545, 0, 0};
Point(2) = {0.2545, 0.04, 0};
Point(3) = {0.2845, 0.04, 0};
Point(4) = {0.2845, 0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
)";

const std::string scene_2d = R"([case]
name = "probes_on_walls"
dimension = 2

[[wall]]
name = "tank"
kind = "rectangle"
origin = [0.0, 0.0]
size = [0.4, 0.3]
faces = ["xmin", "xmax", "ymin"]
mesh_size = 0.01

[[wall]]
name = "obstacle"
kind = "file"
file = "obstacle.geo"
mesh_size = 0.005

[fluid]
dx = 0.0025

[[fluid.region]]
origin = [0.0, 0.0]
size = [0.1, 0.1]

[time]
end = 0.3

[[probe]]
name = "obstacle_face"
kind = "pressure"
position = [0.2545, 0.01]

[[probe]]
name = "obstacle_fluid"
kind = "pressure"
position = [0.25425, 0.01]

[[probe]]
name = "tank_face"
kind = "pressure"
position = [0.0, 0.01]

[[probe]]
name = "tank_fluid"
kind = "pressure"
position = [0.00025, 0.01]
)";

// 3-D: tank 0.3 × 0.05 × 0.2 m, a column 0.08 × 0.05 × 0.08 m, the obstacle a box x ∈ [0.2045,
// 0.2345], y ∈ [0.01, 0.04], z ∈ [0, 0.03] m as a binary STL (0.2045 is not a float: stored as
// 0.20450000464916229 m, 4.6e-9 m beyond the probe's 0.2045).
constexpr double face_3d = 0.2045, dx_3d = 0.005;

const std::string scene_3d = R"([case]
name = "probes_on_walls_3d"
dimension = 3

[[wall]]
name = "tank"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [0.3, 0.05, 0.2]
faces = ["xmin", "xmax", "ymin", "ymax", "zmin"]
mesh_size = 0.02

[[wall]]
name = "obstacle"
kind = "file"
file = "obstacle.stl"
mesh_size = 0.005
flip_normals = true

[fluid]
dx = 0.005

[[fluid.region]]
origin = [0.0, 0.0, 0.0]
size = [0.08, 0.05, 0.08]

[time]
end = 0.3

[[probe]]
name = "obstacle_face"
kind = "pressure"
position = [0.2045, 0.025, 0.01]

[[probe]]
name = "obstacle_fluid"
kind = "pressure"
position = [0.2040, 0.025, 0.01]

[[probe]]
name = "tank_face"
kind = "pressure"
position = [0.0, 0.025, 0.01]

[[probe]]
name = "tank_fluid"
kind = "pressure"
position = [0.0005, 0.025, 0.01]
)";

/// The obstacle box as a binary STL (single precision, as the format is), normals out of it.
void write_box_stl(const fs::path& file, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  std::ofstream out(file, std::ios::binary);
  auto corner = [&](int i) {
    return Eigen::Vector3d(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(),
                           i & 4 ? hi.z() : lo.z());
  };
  // Each face as two triangles, counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  out << std::string(80, ' ');
  const std::uint32_t count = 12;
  out.write(reinterpret_cast<const char*>(&count), 4);  // little-endian host (x86-64)
  for (const auto& f : faces)
    for (const auto& tri :
         {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}}) {
      std::array<float, 12> record{};  // the normal (zero: from the vertex order), 3 vertices
      for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c) record[3 + 3 * k + c] = static_cast<float>(corner(tri[k])[c]);
      out.write(reinterpret_cast<const char*>(record.data()), 48);
      out.write("\0\0", 2);
    }
}

io::Scene write_scene(const std::string& text, const std::string& name) {
  fs::create_directories(folder);
  std::ofstream(folder / "obstacle.geo") << obstacle_geo;
  write_box_stl(folder / "obstacle.stl", {0.2045, 0.01, 0.0}, {0.2345, 0.04, 0.03});
  std::ofstream(folder / name) << text;
  return io::Scene::load(folder / name);
}

/// The probe series of a run to the scene's end: one row per 0.002 s.
template <int D>
std::vector<std::vector<double>> probe_series(const io::Scene& scene) {
  FlowSetup<D> setup = flow_setup<D>(scene, scene_wall_surfaces(scene));
  ldd::FlowSolver<D> flow(std::move(setup.walls), setup.fluid, setup.velocity, setup.options);
  std::vector<std::vector<double>> rows;
  const double end = setup.time.end, interval = 0.002;
  double next = interval;
  while (flow.time() < end - 1e-12) {
    const double to_sample = next - flow.time();
    flow.step(ldd::bounded_step(flow.stable_dt(0.0).first, to_sample));
    if (flow.time() >= next - 1e-12) {
      rows.push_back(coupling::evaluate_probes<D>(flow, std::span(setup.probes)));
      next += interval;
    }
  }
  return rows;
}

/// Compares column `face` with column `fluid` (the probe 0.1 dx inside the fluid): both have a
/// value at the same samples (but for a sample at the surge's arrival), and differ by at most
/// 5 % of the fluid probe's peak.
void expect_face_reads_the_fluid_side(const std::vector<std::vector<double>>& rows,
                                      std::size_t face, std::size_t fluid, const char* what) {
  double peak = 0.0, worst = 0.0;
  int both = 0, only_one = 0;
  for (const auto& row : rows) {
    const bool a = !std::isnan(row[face]), b = !std::isnan(row[fluid]);
    if (a != b) ++only_one;
    if (!(a && b)) continue;
    ++both;
    peak = std::max(peak, std::abs(row[fluid]));
    worst = std::max(worst, std::abs(row[face] - row[fluid]));
  }
  std::printf(
      "%s: %d samples with fluid (%d with fluid at one probe only), peak %.1f Pa, largest "
      "difference %.2f Pa (%.2f %% of the peak)\n",
      what, both, only_one, peak, worst, 100 * worst / peak);
  EXPECT_GT(both, 20) << what;
  EXPECT_LE(only_one, 2) << what;
  EXPECT_GT(peak, 100.0) << what;
  EXPECT_LE(worst, 0.05 * peak) << what;
}

TEST(ProbesOnWalls, FaceProbeReadsTheWallPressure2D) {
  const auto rows = probe_series<2>(write_scene(scene_2d, "scene_2d.toml"));
  expect_face_reads_the_fluid_side(rows, 0, 1, "2-D obstacle (.geo) face");
  expect_face_reads_the_fluid_side(rows, 2, 3, "2-D tank (rectangle) face");
}

TEST(ProbesOnWalls, FaceProbeReadsTheWallPressure3D) {
  const auto rows = probe_series<3>(write_scene(scene_3d, "scene_3d.toml"));
  expect_face_reads_the_fluid_side(rows, 0, 1, "3-D obstacle (STL) face");
  expect_face_reads_the_fluid_side(rows, 2, 3, "3-D tank (box) face");
}

/// The InputError message of setting up `text` ("" when there is none).
template <int D>
std::string setup_error(const std::string& text) {
  try {
    const io::Scene scene = write_scene(text, "scene_error.toml");
    flow_setup<D>(scene, scene_wall_surfaces(scene));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ProbesOnWalls, ProbeInsideTheObstacleIsRefusedWithTheFluidSide) {
  const std::string e =
      setup_error<3>(replaced(scene_3d, "[0.2045, 0.025, 0.01]", "[0.21, 0.025, 0.01]"));
  EXPECT_NE(e.find("probe[0].position = [0.21, 0.025, 0.01]: probe 'obstacle_face' lies 0.0055 m "
                   "inside the solid body 'obstacle'; the nearest point on the fluid side is "
                   "[0.204495, 0.025, 0.01] m"),
            std::string::npos)
      << e;
}

TEST(ProbesOnWalls, ProbeOnAThinWallMustSayItsSide) {
  std::string text =
      replaced(scene_2d, "file = \"obstacle.geo\"", "file = \"baffle.geo\"\nthin = true");
  std::ofstream(folder / "baffle.geo")
      << "Point(1) = {0.2545, 0, 0};\nPoint(2) = {0.2545, 0.04, 0};\n"
         "Line(1) = {1, 2};\n";
  const std::string e = setup_error<2>(text);
  EXPECT_NE(e.find("probe 'obstacle_face' lies on the thin wall 'obstacle'"), std::string::npos)
      << e;
  // A hair off it, on a side: accepted.
  EXPECT_EQ(setup_error<2>(replaced(text, "[0.2545, 0.01]", "[0.2544, 0.01]")), "");
}

TEST(ProbesOnWalls, ProbeWithinTheToleranceBehindAFaceMeasuresOnIt) {
  // 0.02 dx inside the obstacle (a sensor on a curved surface between facets): on the face.
  const io::Scene scene =
      write_scene(replaced(scene_2d, "[0.2545, 0.01]", "[0.25455, 0.01]"), "scene_tolerance.toml");
  const FlowSetup<2> setup = flow_setup<2>(scene, scene_wall_surfaces(scene));
  EXPECT_NEAR(setup.probes[0].position.x(), face_2d - 1e-3 * dx_2d, 1e-12);
  EXPECT_NEAR(setup.probes[0].position.y(), 0.01, 1e-12);
  // The tank's face: moved a hair into the fluid.
  EXPECT_NEAR(setup.probes[2].position.x(), 1e-3 * dx_2d, 1e-12);
}

TEST(ProbesOnWalls, ProbeOnAnStlFaceIsPlacedOnItsFluidSide3D) {
  // The binary STL holds 0.2045 as the float 0.20450000464916229: the probe given at 0.2045
  // lies 4.6e-9 m inside the obstacle, and is placed 0.001 dx in front of the face read.
  const double face = static_cast<double>(static_cast<float>(face_3d));
  ASSERT_GT(face, face_3d);
  const io::Scene scene = write_scene(scene_3d, "scene_3d_setup.toml");
  const FlowSetup<3> setup = flow_setup<3>(scene, scene_wall_surfaces(scene));
  EXPECT_NEAR(setup.probes[0].position.x(), face - 1e-3 * dx_3d, 1e-12);
  EXPECT_DOUBLE_EQ(setup.probes[1].position.x(), 0.2040);  // 0.1 dx in front: kept
}

}  // namespace
}  // namespace hm::driver
