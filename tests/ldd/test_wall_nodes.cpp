// The wall-node spacing (FlowOptions::wall_node_spacing, scene key solver.wall_node_spacing)
// against potential flow: the added mass of a tank wall accelerated into still water, measured
// with the PPE's response to a wall acceleration (FlowSolver::acceleration_pressure, as the
// coupling measures a structure's added mass), must not depend on how densely the wall is
// sampled over the key's range [dx/16, dx].
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "flow_cases.hpp"
#include "ldd/walls.hpp"

namespace hm::ldd {
namespace {

constexpr double kDepth = 0.2, kLength = 0.4, kDensity = 1000.0;

/// Potential flow: the wall x = 0 of a tank [0, L] × [0, H] (floor z = 0, free surface p = 0 at
/// z = H, the far wall fixed) accelerating along +x. p = Σ A_n cos(k_n z) cosh(k_n (L − x)),
/// k_n = (2n − 1)π/(2H), gives m_a = ∫p dz / a = (2ρ/H) Σ coth(k_n L)/k_n³ [kg/m].
double potential_flow_added_mass() {
  double sum = 0.0;
  for (int n = 1; n <= 2000; ++n) {
    const double k = (2 * n - 1) * M_PI / (2 * kDepth);
    sum += 1.0 / (std::tanh(k * kLength) * k * k * k);
  }
  return 2 * kDensity / kDepth * sum;
}

struct AddedMass {
  double value = 0.0;  ///< [kg/m]
  Index wall_nodes = 0;
};

/// `wall_element`: the tank mesh's element size [m] (0: 4 dx); a wall node sits at every vertex.
AddedMass measured_added_mass(double dx, double wall_node_spacing, bool weighted = false,
                              double wall_element = 0.0) {
  FlowOptions<2> options;
  options.wall_node_spacing = wall_node_spacing;
  options.wall_node_weights = weighted;
  Box<2> fluid{Vec<2>::Zero(), Vec<2>(kLength, kDepth)};
  auto flow =
      test::water_in_tank<2>(Vec<2>(kLength, 2 * kDepth), fluid, dx, options, 0.0, wall_element);
  const auto& points = flow.points();
  // Unit acceleration of the wall x = 0 (its nodes face +x), nothing else moves.
  std::vector<Vec<2>> acceleration(static_cast<std::size_t>(points.size()), Vec<2>::Zero());
  AddedMass m;
  for (Index i = 0; i < points.size(); ++i) {
    if (points.kind[i] != PointKind::wall) continue;
    ++m.wall_nodes;
    if (points.position[i].x() < 1e-12 && points.wall_normal[i].x() > 0.5)
      acceleration[i] = Vec<2>(1.0, 0.0);
  }
  const std::vector<double> p = flow.acceleration_pressure(acceleration);
  const auto loads = wall_pressure_loads<2>(points, flow.walls()[0], 0, dx, p);
  const auto& wall = flow.walls()[0];
  for (Index e = 0; e < wall.element_count(); ++e) {
    const auto& c = wall.element(e);
    if (std::abs(wall.vertices()[c[0]].x()) < 1e-12 && std::abs(wall.vertices()[c[1]].x()) < 1e-12)
      m.value -= loads.element_force[e].x();  // the fluid holds the wall back: −m_a a
  }
  return m;
}

// Measured: −3.99 / −3.20 / −3.07 % at dx = H/20 and −2.16 / −1.73 / −1.70 % at H/40 for
// spacings dx, dx/4, dx/16: first order in dx (the free surface sits dx/2 low), the same at
// every spacing. (Finer still, the answer breaks: a wall meshed at dx/32 gave +81 %, which is why
// the key stops at dx/16.)
TEST(WallNodeSpacing, AddedMassOfAnAcceleratedWallMatchesPotentialFlow) {
  const double exact = potential_flow_added_mass();
  std::vector<double> error_at_dx;
  for (const double dx : {0.01, 0.005}) {
    const double at_dx = measured_added_mass(dx, 1.0).value;
    error_at_dx.push_back(std::abs(at_dx / exact - 1));
    for (const double spacing : {1.0, 0.25, 0.0625}) {
      const AddedMass m = measured_added_mass(dx, spacing);
      std::printf(
          "dx %.3f m, wall nodes at %.4f dx: %d wall nodes, added mass %.3f kg/m, "
          "potential flow %.3f kg/m (%+.2f %%)\n",
          dx, spacing, static_cast<int>(m.wall_nodes), m.value, exact, 100 * (m.value / exact - 1));
      EXPECT_NEAR(m.value / exact, 1.0, 0.05) << "dx " << dx << ", spacing " << spacing;
      EXPECT_NEAR(m.value / at_dx, 1.0, 0.015) << "dx " << dx << ", spacing " << spacing;
    }
  }
  EXPECT_LT(error_at_dx[1], 0.7 * error_at_dx[0]) << "no convergence under refinement";
}

// With the wall nodes weighted by the wall length they stand for (solver.wall_node_weights), the
// answer no longer depends on the sampling at all: −4.01 / −4.07 / −3.92 % at H/20 for dx, dx/4,
// dx/16 (and a wall meshed at dx/32 or dx/64 gives −3.93 / −3.94 %, where the unweighted
// operators give +81 / +169 %: the wall nodes' moment matrices fell below λ_c, were
// regularised, and their Neumann rows saw half of n·∇p).
TEST(WallNodeSpacing, WeightedWallNodesMakeTheAddedMassIndependentOfTheSampling) {
  const double exact = potential_flow_added_mass();
  for (const double dx : {0.01, 0.005}) {
    const double at_dx = measured_added_mass(dx, 1.0, true).value;
    for (const double spacing : {1.0, 0.25, 0.0625}) {
      const AddedMass m = measured_added_mass(dx, spacing, true);
      std::printf(
          "weighted, dx %.3f m, wall nodes at %.4f dx: %d wall nodes, added mass %.3f "
          "kg/m (%+.2f %% from potential flow)\n",
          dx, spacing, static_cast<int>(m.wall_nodes), m.value, 100 * (m.value / exact - 1));
      EXPECT_NEAR(m.value / exact, 1.0, 0.05) << "dx " << dx << ", spacing " << spacing;
      EXPECT_NEAR(m.value / at_dx, 1.0, 0.005) << "dx " << dx << ", spacing " << spacing;
    }
    const AddedMass fine_mesh = measured_added_mass(dx, 1.0, true, dx / 32);
    std::printf(
        "weighted, dx %.3f m, the wall meshed at dx/32: %d wall nodes, added mass %.3f "
        "kg/m (%+.2f %%)\n",
        dx, static_cast<int>(fine_mesh.wall_nodes), fine_mesh.value,
        100 * (fine_mesh.value / exact - 1));
    EXPECT_NEAR(fine_mesh.value / at_dx, 1.0, 0.005) << "dx " << dx << ", mesh at dx/32";
  }
}

}  // namespace
}  // namespace hm::ldd
