// A small detailed rigid body in a 3-D tank: an L bracket (legs 20 mm, 4 mm thick, 20 mm wide)
// given as an STL wall, triangulated at 0.5 mm (dx/4) and at 2 mm (dx) with dx = 2 mm. The
// detailed mesh used to put a wall node at every vertex and edge midpoint (13 per dx² of its
// surface), and the fluid on the two faces of its legs, thinner than h, saw each other. Here: the
// nodes are thinned to the node spacing, the closed bracket is a solid body (pairs through its 4 mm
// legs, thinner than h, cut; the floor nodes it covers buried), and the two triangulations give the
// same flow.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include <Eigen/Geometry>

#include "driver/flow_setup.hpp"
#include "ldd/flow.hpp"
#include "ldd/probes.hpp"

namespace hm::driver {
namespace {

namespace fs = std::filesystem;
using ldd::Vec;

const fs::path folder = fs::path(HM_BINARY_DIR) / "tests" / "driver" / "detailed_obstacle";

// The bracket's section in the x–z plane: an L of outer legs a and thickness t; extruded along y.
constexpr double leg = 0.020, thickness = 0.004, width = 0.020;  // m
const Vec<3> corner(0.05, 0.01, 0.0);                            // m: the bracket's lower corner
constexpr double depth = 0.03, dx = 0.002, rho_g = 1000.0 * 9.81;

/// Writes the bracket as a binary STL (single precision, as the numbers of this test were
/// measured with: the dam break's largest PPE iteration count moves from 291 to 384 when the same
/// mesh is read in double precision from ASCII, a change of 1e-8 m in the vertices): every face a
/// grid of squares of side `step` (a divisor of the dimensions, so that the faces' grids
/// conform), two triangles each, normals outward.
void write_bracket_stl(const fs::path& file, double step) {
  std::vector<std::array<float, 12>> records;
  auto facet = [&](const Vec<3>& p, const Vec<3>& q, const Vec<3>& r, const Vec<3>& outward) {
    const Vec<3> n = (q - p).cross(r - p);
    const bool flip = n.dot(outward) < 0.0;
    const Vec<3>& b = flip ? r : q;
    const Vec<3>& c = flip ? q : r;
    std::array<float, 12> record{};
    for (int a = 0; a < 3; ++a)
      record[static_cast<std::size_t>(a)] = static_cast<float>(outward[a]);
    int k = 3;
    for (const Vec<3>* v : {&p, &b, &c})
      for (int a = 0; a < 3; ++a)
        record[static_cast<std::size_t>(k++)] = static_cast<float>((*v)[a]);
    records.push_back(record);
  };
  auto rectangle = [&](const Vec<3>& origin, const Vec<3>& e1, const Vec<3>& e2,
                       const Vec<3>& outward) {
    const int n1 = static_cast<int>(std::lround(e1.norm() / step));
    const int n2 = static_cast<int>(std::lround(e2.norm() / step));
    auto at = [&](int i, int j) -> Vec<3> { return origin + e1 * i / n1 + e2 * j / n2; };
    for (int i = 0; i < n1; ++i)
      for (int j = 0; j < n2; ++j) {
        facet(at(i, j), at(i + 1, j), at(i + 1, j + 1), outward);
        facet(at(i, j), at(i + 1, j + 1), at(i, j + 1), outward);
      }
  };
  const double a = leg, t = thickness;
  const std::vector<std::array<double, 2>> section{{0, 0}, {a, 0}, {a, t}, {t, t}, {t, a}, {0, a}};
  const std::vector<std::array<double, 2>> outward{{0, -1}, {1, 0}, {0, 1},
                                                   {1, 0},  {0, 1}, {-1, 0}};
  const Vec<3> along(0, width, 0);
  for (std::size_t k = 0; k < section.size(); ++k) {
    const auto& p = section[k];
    const auto& q = section[(k + 1) % section.size()];
    rectangle(corner + Vec<3>(p[0], 0, p[1]), Vec<3>(q[0] - p[0], 0, q[1] - p[1]), along,
              Vec<3>(outward[k][0], 0, outward[k][1]));
  }
  for (const double y : {0.0, width}) {
    const Vec<3> side(0, y == 0.0 ? -1 : 1, 0);
    rectangle(corner + Vec<3>(0, y, 0), Vec<3>(a, 0, 0), Vec<3>(0, 0, t), side);
    rectangle(corner + Vec<3>(0, y, t), Vec<3>(t, 0, 0), Vec<3>(0, 0, a - t), side);
  }
  std::ofstream out(file, std::ios::binary);
  out << std::string(80, ' ');
  const auto count = static_cast<std::uint32_t>(records.size());
  out.write(reinterpret_cast<const char*>(&count), 4);  // little-endian host (x86-64)
  for (const auto& record : records) {
    out.write(reinterpret_cast<const char*>(record.data()), 48);
    out.write("\0\0", 2);
  }
}

std::string scene_text(const std::string& stl, const std::array<double, 3>& water) {
  return R"([case]
name = "bracket"
dimension = 3

[[wall]]
name = "tank"
kind = "box"
origin = [0.0, 0.0, 0.0]
size = [0.12, 0.04, 0.05]
faces = ["xmin", "xmax", "ymin", "ymax", "zmin"]
mesh_size = 0.008

[[wall]]
name = "bracket"
kind = "file"
file = ")" +
         stl + R"("
mesh_size = 0.002
flip_normals = true

[fluid]
dx = 0.002

[[fluid.region]]
origin = [0.0, 0.0, 0.0]
size = [)" +
         std::to_string(water[0]) + ", " + std::to_string(water[1]) + ", " +
         std::to_string(water[2]) + R"(]

[time]
end = 0.1
)";
}

ldd::FlowSolver<3> bracket_flow(double step, const std::array<double, 3>& water) {
  fs::create_directories(folder);
  const std::string stl = "bracket_" + std::to_string(static_cast<int>(step * 1e5)) + ".stl";
  write_bracket_stl(folder / stl, step);
  const fs::path scene_file = folder / ("scene_" + stl + ".toml");
  std::ofstream(scene_file) << scene_text(stl, water);
  const io::Scene scene = io::Scene::load(scene_file);
  FlowSetup<3> setup = flow_setup<3>(scene, scene_wall_surfaces(scene));
  return ldd::FlowSolver<3>(std::move(setup.walls), setup.fluid, setup.velocity, setup.options);
}

constexpr int bracket_body = 1;

ldd::Index bracket_nodes(const ldd::FlowSolver<3>& flow) {
  const auto& p = flow.points();
  ldd::Index n = 0;
  for (ldd::Index i = 0; i < p.size(); ++i)
    n += p.kind[i] == ldd::PointKind::wall && p.host[i].body == bracket_body;
  return n;
}

struct RunReport {
  int max_iterations = 0;
  bool converged = true;
  double max_bracket_pressure = 0;  ///< largest pressure on a bracket node over the run [Pa]
  std::vector<double> force_x;      ///< bracket force along x at every 0.01 s [N]
  Vec<3> force = Vec<3>::Zero();    ///< at the end [N]
};

RunReport run(ldd::FlowSolver<3>& flow, double end) {
  RunReport r;
  double next_sample = 0.01;
  while (flow.time() < end - 1e-12) {
    const auto m = flow.step(ldd::bounded_step(flow.stable_dt(0.0).first, end - flow.time()));
    r.max_iterations = std::max(r.max_iterations, m.ppe_iterations);
    r.converged = r.converged && m.ppe_converged;
    const auto& p = flow.points();
    for (ldd::Index i = 0; i < p.size(); ++i)
      if (p.kind[i] == ldd::PointKind::wall && p.host[i].body == bracket_body)
        r.max_bracket_pressure = std::max(r.max_bracket_pressure, p.pressure[i]);
    if (flow.time() >= next_sample - 1e-12) {
      const auto loads =
          ldd::wall_pressure_loads<3>(p, flow.walls()[bracket_body], bracket_body, dx);
      r.force_x.push_back(loads.total.x());
      r.force = loads.total;
      next_sample += 0.01;
    }
  }
  return r;
}

// At rest the wetted faces carry ρg(H − z): the force is the buoyancy ρgV less the pressure the
// floor keeps off the covered base, F_z = ρg(V − H·A_base), and F_x = F_y = 0.
TEST(DetailedObstacle, BracketInWaterAtRestFeelsTheHydrostaticForce) {
  const double volume = (leg * thickness + thickness * (leg - thickness)) * width;
  const double expected_fz = rho_g * (volume - depth * leg * width);  // −0.0895 N
  const double area = 2 * (leg * thickness + thickness * (leg - thickness)) +
                      (4 * leg) * width;  // the wetted faces: two L caps, the sides and top
  std::vector<ldd::Index> nodes;
  for (const double step : {0.0005, 0.002}) {
    auto flow = bracket_flow(step, {0.12, 0.04, depth});
    nodes.push_back(bracket_nodes(flow));
    const RunReport r = run(flow, 0.05);
    std::printf(
        "bracket at %.1f mm: %d nodes (%.2f per dx² of its surface), max %d PPE iterations, "
        "peak node pressure %.0f Pa (rho g H = %.0f Pa), force [%.2e, %.2e, %.4f] N "
        "(expected [0, 0, %.4f])\n",
        1e3 * step, nodes.back(), nodes.back() * dx * dx / (area + leg * width), r.max_iterations,
        r.max_bracket_pressure, rho_g * depth, r.force.x(), r.force.y(), r.force.z(), expected_fz);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(r.max_iterations, 100);
    EXPECT_LT(r.max_bracket_pressure, 1.05 * rho_g * depth);
    EXPECT_NEAR(r.force.z(), expected_fz, 0.1 * std::abs(expected_fz));
    EXPECT_LT(std::abs(r.force.x()), 0.05 * std::abs(expected_fz));
    EXPECT_LT(std::abs(r.force.y()), 0.05 * std::abs(expected_fz));
  }
  // Thinned to the spacing, the 0.5 mm mesh (3 600 vertices) holds about a node per dx² of its
  // surface (measured 0.79); the 2 mm mesh, not finer than the spacing, keeps a node at every
  // vertex and edge midpoint (3.3 per dx²) and gives the same force.
  const double surface = area + leg * width;
  EXPECT_GT(nodes[0] * dx * dx / surface, 0.6);
  EXPECT_LT(nodes[0] * dx * dx / surface, 1.3);
}

// A dam break onto the bracket (a column 40 mm long and high, the bracket 10 mm beyond it): the
// two triangulations feel the same force over the impact, with bounded PPE iterations. Before
// the thinning and the solid obstacle: at rest F_z = −0.047 N instead of −0.0895 N (the floor
// under the bracket was wetted through it), a node pressure of 606 Pa where ρgH = 294 Pa, and
// 366 PPE iterations; here −0.0894 N, 289 Pa, 46 iterations.
TEST(DetailedObstacle, DamBreakOntoTheBracketDoesNotDependOnItsTriangulation) {
  std::vector<RunReport> r;
  for (const double step : {0.0005, 0.002}) {
    auto flow = bracket_flow(step, {0.04, 0.04, 0.04});
    r.push_back(run(flow, 0.08));
    std::printf("bracket at %.1f mm: max %d PPE iterations, peak node pressure %.0f Pa, fx:",
                1e3 * step, r.back().max_iterations, r.back().max_bracket_pressure);
    for (double f : r.back().force_x) std::printf(" %.4f", f);
    std::printf(" N\n");
    EXPECT_TRUE(r.back().converged);
    EXPECT_LT(r.back().max_iterations, 350);  // measured 133 and 291; 426 and 414 unthinned
  }
  ASSERT_EQ(r[0].force_x.size(), r[1].force_x.size());
  double peak = 0, gap = 0;
  for (std::size_t k = 0; k < r[0].force_x.size(); ++k) {
    peak = std::max(peak, std::abs(r[1].force_x[k]));
    gap = std::max(gap, std::abs(r[0].force_x[k] - r[1].force_x[k]));
  }
  std::printf("peak fx %.4f N, largest difference %.4f N\n", peak, gap);
  // Measured: 0.041 N of a 0.153 N peak (0.096 N unthinned and not solid). The impact on the
  // bracket's corner is chaotic at 2 mm, so the two runs differ by more than at rest.
  EXPECT_LT(gap, 0.35 * peak);
}

}  // namespace
}  // namespace hm::driver
