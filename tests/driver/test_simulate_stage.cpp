// fsi-simulate in process on the smoke variant of pipelines/hydrostatic_tank (water 1.0 × 0.5 m
// at rest, dx = 0.02 m, 0.2 s): the probes in probes.csv and results.h5 against hydrostatics,
// the monitors, and the artefact's run attributes.
#include <gtest/gtest.h>

#include <cmath>

#include "driver/simulate_stage.hpp"
#include "io/artefact.hpp"
#include "io/probe_csv.hpp"

namespace hm::driver {
namespace {

namespace fs = std::filesystem;

TEST(SimulateStage, HydrostaticTankSmoke) {
  const fs::path scene_file =
      fs::path(HM_SOURCE_DIR) / "pipelines" / "hydrostatic_tank" / "scene.smoke.toml";
  const fs::path out = fs::path(HM_BINARY_DIR) / "tests" / "driver" / "hydrostatic_smoke";
  fs::remove_all(out);
  const io::Scene scene = io::Scene::load(scene_file);
  run_simulate_stage(scene, {}, out / "results.h5");

  const double rho_g = 1000.0 * 9.81, depth = 0.5, width = 1.0, dx = 0.02;
  const io::ProbeTable csv = io::read_probe_csv(out / "probes.csv");
  ASSERT_EQ(csv.rows(), 21u);  // every 0.01 s from 0 to 0.2 s
  EXPECT_NEAR(csv.column("t [s]").back(), 0.2, 1e-15);
  double worst_p = 0, worst_spread = 0, worst_force = 0;
  for (std::size_t r = 0; r < csv.rows(); ++r) {
    worst_p =
        std::max({worst_p, std::abs(csv.column("p_low.p [Pa]")[r] / (rho_g * (depth - 0.1)) - 1),
                  std::abs(csv.column("p_mid.p [Pa]")[r] / (rho_g * (depth - 0.25)) - 1)});
    const double a = csv.column("eta_left.eta [m]")[r], b = csv.column("eta_mid.eta [m]")[r],
                 c = csv.column("eta_right.eta [m]")[r];
    worst_spread = std::max(worst_spread, std::max({a, b, c}) - std::min({a, b, c}));
    EXPECT_NEAR(b, depth, dx / 4);
    worst_force = std::max(worst_force,
                           std::abs(csv.column("tank.fy [N]")[r] / (-rho_g * depth * width) - 1));
    EXPECT_LT(std::abs(csv.column("tank.fx [N]")[r]), 1e-6 * rho_g * depth * width);
  }
  std::printf(
      "hydrostatic smoke: pressure error %.3f %%, surface spread %.2f mm (dx/4 = %.1f "
      "mm), floor force error %.3f %%\n",
      100 * worst_p, 1e3 * worst_spread, 250 * dx, 100 * worst_force);
  EXPECT_LT(worst_p, 0.01);  // issue 6: within 1 % of ρg(H − z)
  EXPECT_LT(worst_spread, dx / 4);
  EXPECT_LT(worst_force, 0.01);

  const io::ArtefactReader results(out / "results.h5", io::results_schema());
  EXPECT_EQ(results.provenance().status, "ok");
  EXPECT_EQ(results.string_attribute(io::results_attr::run_status), "completed");
  EXPECT_EQ(results.number_attribute(io::results_attr::points), 25.0 * 50.0);
  const auto drift = results.read_values(io::ds::monitor_volume_drift);
  const auto escaped = results.read_index_values(io::ds::monitor_escaped);
  const auto time = results.read_values(io::ds::monitor_time);
  ASSERT_FALSE(time.empty());
  EXPECT_NEAR(time.back(), 0.2, 1e-15);
  double worst_drift = 0;
  for (double d : drift) worst_drift = std::max(worst_drift, std::abs(d));
  EXPECT_LT(worst_drift, 0.005);
  EXPECT_EQ(escaped.back(), 0);
  // The same probe series in the artefact as in the CSV.
  const io::MatrixRM values = results.read_matrix(io::ds::probe_values);
  ASSERT_EQ(values.rows(), 21);
  EXPECT_EQ(values(20, 0), csv.column("p_low.p [Pa]")[20]);
  EXPECT_EQ(results.string_attribute(io::results_attr::probe_columns),
            "p_low.p [Pa],p_mid.p [Pa],eta_left.eta [m],eta_mid.eta [m],eta_right.eta [m],"
            "tank.fx [N],tank.fy [N]");
  EXPECT_TRUE(fs::exists(out / "snapshots" / "flow.xdmf"));
}

}  // namespace
}  // namespace hm::driver
