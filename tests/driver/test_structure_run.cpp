// fsi-simulate on a structure-only scene, in process: the pipeline cantilever_tip_load (smoke
// variant) through fsi-mesh → fsi-modes → fsi-simulate, its tip probe against the corrected
// analytic step response on the same modes (LDD-SPEC §2.2: the mode-shape factors and the
// ζ/√(1 − ζ²) sin term of the paper's eq. 19), and the load histories and bad inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "coupling/structure_run.hpp"
#include "driver/mesh_stage.hpp"
#include "driver/modes_stage.hpp"
#include "driver/simulate_stage.hpp"
#include "driver/structure_io.hpp"
#include "io/artefact.hpp"
#include "io/scene.hpp"

namespace fs = std::filesystem;
using namespace hm;

namespace {

using hm::test::fresh_dir;
using hm::test::read_text;

/// The cantilever smoke scene with `replace` substituted for `find` (or unchanged).
io::Scene cantilever(const fs::path& dir, const std::string& find = "",
                     const std::string& replace = "") {
  std::string text = read_text(HM_SOURCE_DIR "/pipelines/cantilever_tip_load/scene.smoke.toml");
  if (!find.empty()) {
    const auto at = text.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    text.replace(at, find.size(), replace);
  }
  std::ofstream(dir / "scene.toml") << text;
  return io::Scene::load(dir / "scene.toml");
}

/// Corrected analytic response of mode set `m` at DOF `dof` to the step load f applied at t = 0.
double analytic(const modal::ModeSet& m, const Eigen::VectorXd& f, Eigen::Index dof, double t) {
  double u = 0.0;
  for (int i = 0; i < m.count(); ++i) {
    const double w = m.omega[i], z = m.damping_ratio[i], wd = w * std::sqrt(1 - z * z);
    u += m.shapes(dof, i) * m.shapes.col(i).dot(f) / (w * w) *
         (1 -
          std::exp(-z * w * t) * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t)));
  }
  return u;
}

TEST(StructureRun, CantileverTipLoadMatchesTheCorrectedAnalyticResponse) {
  const fs::path dir = fresh_dir("cantilever");
  const io::Scene scene = cantilever(dir);
  driver::run_mesh_stage(scene, dir / "mesh.h5");
  driver::run_modes_stage(scene, dir / "mesh.h5", dir / "modes.h5");
  driver::run_simulate_stage(scene, {.mesh = dir / "mesh.h5", .modes = dir / "modes.h5"},
                             dir / "results.h5");

  const auto mesh =
      driver::read_structure_mesh(io::ArtefactReader(dir / "mesh.h5", io::mesh_schema()));
  const auto modes =
      driver::read_mode_set(io::ArtefactReader(dir / "modes.h5", io::modes_schema()));
  const io::ArtefactReader results(dir / "results.h5", io::results_schema());
  ASSERT_EQ(results.string_attribute("probe_columns").value_or(""), "tip.ux [m],tip.uy [m]");
  const io::MatrixRM probes = results.read_matrix(io::ds::probe_values);
  const std::vector<double> time = results.read_values(io::ds::probe_time);
  ASSERT_EQ(time.size(), 1001u);  // every step of 1e-4 s to 0.1 s, and t = 0

  Eigen::Index tip = 0;
  (mesh.structure.nodes.rowwise() - Eigen::RowVector2d(0.079, 0.0025))
      .rowwise()
      .squaredNorm()
      .minCoeff(&tip);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * mesh.structure.node_count());
  const auto& edge = mesh.structure.node_groups.at("xmax");
  for (auto node : edge) f[2 * node + 1] = 1.0 / static_cast<double>(edge.size());
  double worst = 0.0, peak = 0.0;
  for (std::size_t k = 0; k < time.size(); ++k) {
    const double exact = analytic(modes, f, 2 * tip + 1, time[k]);
    worst = std::max(worst, std::abs(probes(static_cast<Eigen::Index>(k), 1) - exact));
    peak = std::max(peak, std::abs(exact));
  }
  std::printf(
      "cantilever tip load, %d modes (f1 = %.3f Hz): peak tip deflection %.4e m, max "
      "|CFPI − analytic| / peak = %.2e over %zu steps\n",
      modes.count(), modes.frequency_hz[0], peak, worst / peak, time.size() - 1);
  EXPECT_LT(worst / peak, 1e-8);
  // The modal datasets: y at the end reproduces the probe through the shapes.
  const io::MatrixRM y = results.read_matrix(io::ds::modal_coordinates);
  EXPECT_NEAR(modes.shapes.row(2 * tip + 1).dot(y.row(y.rows() - 1)), probes(probes.rows() - 1, 1),
              1e-15);
}

TEST(StructureRun, StaticStartStaysAtTheStaticSolution) {
  // y(0) = F(0)/ω² under a constant load is an equilibrium: the tip does not move.
  const fs::path dir = fresh_dir("static");
  const io::Scene scene = cantilever(dir, "[structure]\n", "[structure]\nstatic_start = true\n");
  driver::run_mesh_stage(scene, dir / "mesh.h5");
  driver::run_modes_stage(scene, dir / "mesh.h5", dir / "modes.h5");
  driver::run_simulate_stage(scene, {.mesh = dir / "mesh.h5", .modes = dir / "modes.h5"},
                             dir / "results.h5");
  const io::MatrixRM probes = io::ArtefactReader(dir / "results.h5", io::results_schema())
                                  .read_matrix(io::ds::probe_values);
  const double start = probes(0, 1);
  double drift = 0.0;
  for (Eigen::Index r = 0; r < probes.rows(); ++r)
    drift = std::max(drift, std::abs(probes(r, 1) - start));
  std::printf("static start: tip %.6e m, largest change %.2e m\n", start, drift);
  EXPECT_GT(start, 1e-3);  // the 5-mode static deflection, 1.10e-3 m
  EXPECT_LT(drift, 1e-12 * start);
}

TEST(StructureRun, LoadHistories) {
  coupling::LoadHistory ramp{.kind = coupling::LoadHistory::Kind::ramp, .ramp_time = 0.2};
  EXPECT_DOUBLE_EQ(ramp(0.05), 0.25);
  EXPECT_DOUBLE_EQ(ramp(0.5), 1.0);
  coupling::LoadHistory sine{
      .kind = coupling::LoadHistory::Kind::harmonic, .frequency = 2.0, .phase = 0.5};
  EXPECT_NEAR(sine(0.1), std::sin(2 * M_PI * 2.0 * 0.1 + 0.5), 1e-15);
  coupling::LoadHistory table{.kind = coupling::LoadHistory::Kind::table,
                              .table_time = {0.0, 1.0, 2.0},
                              .table_factor = {0.0, 2.0, 1.0},
                              .table_file = "f.csv"};
  EXPECT_DOUBLE_EQ(table(0.25), 0.5);
  EXPECT_DOUBLE_EQ(table(1.5), 1.5);
  try {
    table(2.5);
    FAIL() << "outside the table";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("f.csv: the load table covers t = 0 … 2 s"),
              std::string::npos)
        << e.what();
  }
}

TEST(StructureRun, BadInputsNameTheKey) {
  const fs::path dir = fresh_dir("bad");
  auto message = [&](const std::string& find, const std::string& replace) {
    try {
      const io::Scene scene = cantilever(dir, find, replace);
      driver::run_mesh_stage(scene, dir / "mesh.h5");
      driver::run_modes_stage(scene, dir / "mesh.h5", dir / "modes.h5");
      driver::run_simulate_stage(scene, {.mesh = dir / "mesh.h5", .modes = dir / "modes.h5"},
                                 dir / "results.h5");
    } catch (const std::exception& e) {
      EXPECT_FALSE(fs::exists(dir / "results.h5"));
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("group = \"xmax\"", "group = \"xmx\"")
                .find("load[0].group = \"xmx\" is not a node group of the structure mesh: "
                      "expected one of"),
            std::string::npos);
  EXPECT_NE(message("group = \"xmax\"", "group = \"xmx\"").find("did you mean \"xmax\"?"),
            std::string::npos);
  EXPECT_NE(message("force = [0.0, 1.0]", "force = [0.0, 1.0, 0.0]")
                .find("load[0].force = [0, 1, 0] has 3 values, expected 2"),
            std::string::npos);
  EXPECT_NE(message("history = \"constant\"", "history = \"ramp\"")
                .find("history = \"ramp\" needs ramp_time > 0 (s)"),
            std::string::npos);
  EXPECT_NE(message("kind = \"displacement\"", "kind = \"pressure\"")
                .find("a structure-only run (no [fluid]) has displacement probes only"),
            std::string::npos);
  const io::Scene scene = cantilever(dir);
  try {
    driver::run_simulate_stage(scene, {.mesh = dir / "mesh.h5"}, dir / "results.h5");
    FAIL() << "no --modes";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find("give --mesh mesh.h5 (the node groups) and --modes"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
