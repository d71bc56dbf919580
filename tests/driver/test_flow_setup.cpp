// The flow of a scene (driver/flow_setup): seeding of overlapping regions, wall motions, probes,
// and the validation errors of the flow keys, each naming file:line: key.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>

#include "../common/replaced.hpp"
#include "driver/flow_setup.hpp"

using hm::test::replaced;

namespace hm::driver {
namespace {

namespace fs = std::filesystem;

const fs::path folder = fs::path(HM_BINARY_DIR) / "tests" / "driver" / "flow_setup";

const std::string tank_scene = R"([case]
name = "tank"
dimension = 2

[[wall]]
name = "tank"
kind = "rectangle"
origin = [0.0, 0.0]
size = [1.0, 0.6]
faces = ["xmin", "xmax", "ymin"]
mesh_size = 0.02
motion = "sway"
sway_amplitude = 0.01
sway_period = 1.0

[fluid]
dx = 0.01

[[fluid.region]]
origin = [0.0, 0.0]
size = [0.2, 0.1]

[[fluid.region]]
origin = [0.1, 0.0]
size = [0.2, 0.1]
velocity = [0.1, 0.0]

[time]
end = 0.05

[[probe]]
name = "p1"
kind = "pressure"
position = [0.05, 0.02]

[[probe]]
name = "gauge"
kind = "elevation"
position = [0.05, 0.0]

[[probe]]
name = "surge"
kind = "front"

[[probe]]
name = "load"
kind = "force"
wall = "tank"
)";

io::Scene scene_from(const std::string& text) {
  fs::create_directories(folder);
  return io::Scene::parse(text, folder / "scene.toml");
}

/// The InputError message of setting up `text` ("" when there is none).
std::string setup_error(const std::string& text) {
  try {
    const io::Scene scene = scene_from(text);
    flow_setup<2>(scene, scene_wall_surfaces(scene));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(FlowSetup, SeedsOverlappingRegionsOnce) {
  const io::Scene scene = scene_from(tank_scene);
  const FlowSetup<2> setup = flow_setup<2>(scene, scene_wall_surfaces(scene));
  // 0.3 m × 0.1 m at dx = 0.01: 30 × 10 lattice points, the overlap [0.1, 0.2] seeded once.
  ASSERT_EQ(setup.fluid.size(), 300u);
  double closest = 1e300;
  for (std::size_t i = 0; i < setup.fluid.size(); ++i)
    for (std::size_t j = i + 1; j < setup.fluid.size(); ++j)
      closest = std::min(closest, (setup.fluid[i] - setup.fluid[j]).norm());
  EXPECT_NEAR(closest, 0.01, 1e-12);
  for (std::size_t i = 0; i < setup.fluid.size(); ++i) {
    const double expected = setup.fluid[i][0] > 0.2 ? 0.1 : 0.0;  // the second region's velocity
    EXPECT_EQ(setup.velocity[i], ldd::Vec<2>(expected, 0.0)) << setup.fluid[i].transpose();
  }
  EXPECT_EQ(setup.options.dx, 0.01);
  EXPECT_EQ(setup.options.gravity, ldd::Vec<2>(0.0, -9.81));
  EXPECT_EQ(setup.options.density, 1000.0);
  EXPECT_EQ(setup.time.end, 0.05);
}

TEST(FlowSetup, BuildsTheSwayMotionAndPlacesTheWallsAtTimeZero) {
  const io::Scene scene = scene_from(tank_scene);
  const FlowSetup<2> setup = flow_setup<2>(scene, scene_wall_surfaces(scene));
  ASSERT_EQ(setup.motions.size(), 1u);
  ASSERT_TRUE(setup.motions[0].motion.has_value());
  const motion::RigidState quarter = setup.motions[0].motion->state(0.25);
  EXPECT_NEAR(quarter.translation.x(), 0.01, 1e-15);  // A sin(2π·0.25/1)
  // At t = 0 the tank is at x0 and moves at A·2π/T along x.
  EXPECT_LT(
      (setup.walls[0].vertices()[3] - ldd::Vec<2>(setup.motions[0].x0.row(3).transpose())).norm(),
      1e-15);
  EXPECT_NEAR(setup.walls[0].velocity_at(0, ldd::Vec<2>(0.5, 0.5))[0], 0.01 * 2 * std::numbers::pi,
              1e-14);
}

TEST(FlowSetup, ProbesWithColumnsAndDefaults) {
  const io::Scene scene = scene_from(tank_scene);
  const FlowSetup<2> setup = flow_setup<2>(scene, scene_wall_surfaces(scene));
  ASSERT_EQ(setup.probes.size(), 4u);
  EXPECT_EQ(setup.probes[0].radius, 2.5 * 0.01);  // 0: h = support_factor · dx
  EXPECT_EQ(setup.probes[2].direction, ldd::Vec<2>(1.0, 0.0));
  EXPECT_EQ(setup.probes[2].band_low, 0.0);  // the floor is at y = 0
  EXPECT_EQ(setup.probes[2].band_high, 0.02);
  EXPECT_EQ(setup.probes[3].wall, 0);
  const auto columns = coupling::probe_columns<2>(setup.probes);
  EXPECT_EQ(columns, (std::vector<std::string>{"p1.p [Pa]", "gauge.eta [m]", "surge.front [m]",
                                               "load.fx [N]", "load.fy [N]"}));
}

TEST(FlowSetup, TableMotionFromCsvRelativeToTheScene) {
  fs::create_directories(folder);
  std::ofstream(folder / "sway.csv") << "t [s], x [m]\n0, 0\n0.5, 0.005\n1, 0.01\n1.5, 0.015\n";
  const std::string text =
      replaced(replaced(replaced(tank_scene, "motion = \"sway\"", "motion = \"table\""),
                        "sway_amplitude = 0.01", "motion_table = \"sway.csv\""),
               "sway_period = 1.0", "");
  const io::Scene scene = scene_from(text);
  const FlowSetup<2> setup = flow_setup<2>(scene, scene_wall_surfaces(scene));
  const motion::RigidState s = setup.motions[0].motion->state(0.75);
  EXPECT_NEAR(s.translation.x(), 0.0075, 1e-15);  // a line is reproduced by the cubic spline
  EXPECT_NEAR(s.velocity.x(), 0.01, 1e-14);
  ASSERT_EQ(setup.motion_tables.size(), 1u);
  EXPECT_EQ(setup.motion_tables[0], folder / "sway.csv");
}

TEST(FlowSetupErrors, SwayWithoutPeriod) {
  const std::string e = setup_error(replaced(tank_scene, "sway_period = 1.0", ""));
  EXPECT_NE(e.find("scene.toml:12: wall[0].motion: motion = \"sway\" needs sway_amplitude (m) "
                   "and sway_period (s)"),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, RollWithoutPivotAndRollAxisIn2D) {
  std::string text = replaced(tank_scene, "motion = \"sway\"", "motion = \"roll\"");
  text = replaced(text, "sway_amplitude = 0.01", "roll_amplitude = 0.05");
  text = replaced(text, "sway_period = 1.0", "roll_frequency = 0.5");
  std::string e = setup_error(text);
  EXPECT_NE(e.find("wall[0].motion: motion = \"roll\" needs roll_pivot (m)"), std::string::npos)
      << e;
  text = replaced(text, "roll_frequency = 0.5",
                  "roll_frequency = 0.5\nroll_pivot = [0.5, 0.0]\n"
                  "roll_axis = [0.0, 1.0, 0.0]");
  e = setup_error(text);
  EXPECT_NE(e.find("wall[0].roll_axis: a 2-D case always rolls about z"), std::string::npos) << e;
}

TEST(FlowSetupErrors, MotionKeyWithoutItsMotion) {
  const std::string e = setup_error(replaced(tank_scene, "motion = \"sway\"", ""));
  EXPECT_NE(e.find("wall[0].sway_amplitude is given but wall[0].motion = \"none\""),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, ForceProbeOnAnUnknownWall) {
  const std::string e = setup_error(replaced(tank_scene, "wall = \"tank\"", "wall = \"tnak\""));
  EXPECT_NE(e.find("scene.toml:48: probe[3].wall = \"tnak\" is not a wall of the scene: expected "
                   "one of tank (did you mean \"tank\"?)"),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, ProbeNames) {
  std::string e = setup_error(replaced(tank_scene, "name = \"gauge\"", "name = \"p1\""));
  EXPECT_NE(e.find("probe[1].name = \"p1\": another probe has this name"), std::string::npos) << e;
  e = setup_error(replaced(tank_scene, "name = \"gauge\"", "name = \"gauge-1\""));
  EXPECT_NE(e.find("probe[1].name = \"gauge-1\": a probe name is letters, digits and _ only"),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, ProbeOutsideTheWalls) {
  const std::string e =
      setup_error(replaced(tank_scene, "position = [0.05, 0.02]", "position = [1.5, 0.02]"));
  EXPECT_NE(e.find("scene.toml:34: probe[0].position = [1.5, 0.02] is outside the walls' "
                   "bounding box [0, 0] – [1, 0.6] m"),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, RegionOutsideTheWalls) {
  const std::string e =
      setup_error(replaced(tank_scene, "origin = [0.1, 0.0]", "origin = [0.9, 0.0]"));
  EXPECT_NE(e.find("scene.toml:24: fluid.region[1].origin (size [0.2, 0.1]): fluid box (0.9, "
                   "0)–(1.1, 0.1) is not inside the tank"),
            std::string::npos)
      << e;
}

TEST(FlowSetupErrors, FlowSceneWithoutTime) {
  const std::string e = setup_error(replaced(tank_scene, "[time]\nend = 0.05", ""));
  EXPECT_NE(e.find("scene.toml: a flow scene ([fluid]) needs a [time] section"), std::string::npos)
      << e;
}

}  // namespace
}  // namespace hm::driver
