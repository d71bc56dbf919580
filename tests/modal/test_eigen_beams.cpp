// Cantilevers against beam theory: a slender 3-D square beam (tet10) against Timoshenko, with
// the observed convergence order of f1; the 2-D elastic gate (tri6, plane strain) against
// Euler–Bernoulli, and the modal reconstruction of its static tip deflection.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "fem/static_solve.hpp"
#include "mesh/structured.hpp"
#include "modal/modes.hpp"
#include "test_eigen_checks.hpp"

namespace hm::modal {
namespace {

using testing::expect_mode_invariants;
using testing::timoshenko_cantilever_roots;

TEST(TimoshenkoOracle, ReducesToEulerBernoulli) {
  // r, s → 0: βL = 1.87510407, 4.69409113, 7.85475744; Ω = (βL)².
  const std::vector<double> roots = timoshenko_cantilever_roots(0.0, 0.0, 3);
  for (auto [root, beta_l] :
       {std::pair{roots[0], 1.87510407}, {roots[1], 4.69409113}, {roots[2], 7.85475744}})
    EXPECT_NEAR(root, beta_l * beta_l, 1e-7 * root);
}

// Steel beam, square section h × h, L/h = 20, clamped at x = 0.
constexpr double kLength = 1.0, kSide = 0.05;
const fem::ElasticModel kSteel{{2.1e11, 0.3, 7850.0}};

ModeSet beam_modes(int cells_across, int count) {
  const mesh::StructureMesh m =
      mesh::structured_box(kLength, kSide, kSide, 20 * cells_across, cells_across, cells_across);
  return compute_modes(m, kSteel, std::vector<std::string>{"xmin"}, {count, {}, "beam"}, {},
                       Eigen::Vector3d::Zero(), {}, "beam");
}

/// Timoshenko bending frequencies [Hz] of the beam, shear coefficient κ = 10(1+ν)/(12+11ν).
std::vector<double> timoshenko_frequencies(int count) {
  const double e = kSteel.material.youngs_modulus_pa, nu = kSteel.material.poisson_ratio;
  const double area = kSide * kSide, inertia = std::pow(kSide, 4) / 12.0;
  const double kappa = 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu);
  const double shear = kappa * e / (2.0 * (1.0 + nu)) * area;
  const double r2 = inertia / (area * kLength * kLength);
  const double s2 = e * inertia / (shear * kLength * kLength);
  const double scale =
      std::sqrt(e * inertia / (kSteel.material.density_kg_m3 * area)) / (kLength * kLength);
  std::vector<double> f;
  for (double omega : timoshenko_cantilever_roots(r2, s2, count))
    f.push_back(omega * scale / (2.0 * std::numbers::pi));
  return f;
}

/// Bending modes have a transverse (y or z) effective mass; torsion and axial modes have none.
std::vector<int> bending_modes(const ModeSet& modes) {
  const double total = modes.translational_effective_mass.colwise().sum().maxCoeff();
  std::vector<int> bending;
  for (int i = 0; i < modes.count(); ++i) {
    const double transverse =
        modes.translational_effective_mass(i, 1) + modes.translational_effective_mass(i, 2);
    if (transverse > 1e-3 * total) bending.push_back(i);
  }
  return bending;
}

TEST(SlenderCantilever3D, BendingPairsMatchTimoshenko) {
  const ModeSet modes = beam_modes(3, 8);  // 60×3×3 cells, 17 640 free DOFs
  expect_mode_invariants(modes);
  const std::vector<int> bending = bending_modes(modes);
  ASSERT_GE(bending.size(), 4u);
  const std::vector<double> reference = timoshenko_frequencies(2);
  for (int k = 0; k < 4; ++k) {
    const double f = modes.frequency_hz(bending[static_cast<std::size_t>(k)]);
    const double expected = reference[static_cast<std::size_t>(k / 2)];
    std::printf("bending mode %d (index %d): FE %.4f Hz, Timoshenko %.4f Hz, rel. diff %+.2e\n",
                k + 1, bending[static_cast<std::size_t>(k)], f, expected, f / expected - 1);
    EXPECT_NEAR(f, expected, 1e-2 * expected);
  }
  // The square section makes each bending frequency a pair; the Kuhn tetrahedra are not
  // symmetric under y ↔ z, so the discretisation splits each pair by less than its own error.
  for (int k : {0, 2}) {
    const double f = modes.frequency_hz(bending[static_cast<std::size_t>(k)]);
    const double split = modes.frequency_hz(bending[static_cast<std::size_t>(k + 1)]) - f;
    EXPECT_LT(std::abs(split), 1e-3 * f) << "pair " << k / 2 + 1;
  }
}

/// p with (f_a − f_b)/(f_b − f_c) = (a^-p − b^-p)/(b^-p − c^-p) for meshes a, b, c cells across
/// (f_n = f* + C n^-p), by bisection.
double observed_order(const std::array<int, 3>& n, const std::array<double, 3>& f) {
  const double ratio = (f[0] - f[1]) / (f[1] - f[2]);
  auto model = [&](double p) {
    return (std::pow(n[0], -p) - std::pow(n[1], -p)) / (std::pow(n[1], -p) - std::pow(n[2], -p));
  };
  double lo = 0.5, hi = 12.0;  // model(p) increases with p
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (model(mid) < ratio ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Convergence of f1 under uniform refinement. Quadratic elements: eigenvalue (and frequency)
// error O(h⁴) when the eigenfunction is smooth (H³). A clamped cantilever is not: the
// clamped–free corners carry a stress singularity, and its order drops towards 1–1.5 (measured
// below, not asserted). Free-free, the 2-D tri6 beam reaches the theoretical order 4
// (measured 3.8, 3.9 on the pairs 4/8, 8/16 cells across); the 3-D tet10 box settles at 3.5
// (measured on L/h = 20 and L/h = 5 boxes alike, 2–6 cells across), which we attribute to the
// weaker regularity at the box's edges and corners; its bound is set 0.2 below that measurement.
struct Refinement {
  std::array<int, 3> cells_across;
  std::array<double, 3> f;
};

Refinement free_free_2d() {
  Refinement r{{4, 8, 16}, {}};
  for (std::size_t k = 0; k < 3; ++k) {
    const int n = r.cells_across[k];
    const ModeSet modes =
        compute_modes(mesh::structured_rectangle(1.0, 0.05, 20 * n, n),
                      {kSteel.material, fem::PlaneAssumption::plane_stress, 1.0}, {},
                      {4, {}, "beam"}, {}, Eigen::Vector3d::Zero(), {}, "beam");
    expect_mode_invariants(modes);
    r.f[k] = modes.frequency_hz(3);  // after the three rigid-body modes
  }
  return r;
}

Refinement clamped_2d() {
  Refinement r{{4, 8, 16}, {}};
  for (std::size_t k = 0; k < 3; ++k) {
    const int n = r.cells_across[k];
    const ModeSet modes = compute_modes(mesh::structured_rectangle(1.0, 0.05, 20 * n, n),
                                        {kSteel.material, fem::PlaneAssumption::plane_stress, 1.0},
                                        std::vector<std::string>{"xmin"}, {1, {}, "beam"}, {},
                                        Eigen::Vector3d::Zero(), {}, "beam");
    expect_mode_invariants(modes);
    r.f[k] = modes.frequency_hz(0);
  }
  return r;
}

Refinement free_free_3d() {
  Refinement r{{3, 4, 6}, {}};
  for (std::size_t k = 0; k < 3; ++k) {
    const int n = r.cells_across[k];
    const ModeSet modes =
        compute_modes(mesh::structured_box(0.25, 0.05, 0.035, 5 * n, n, n), kSteel, {},
                      {7, {}, "beam"}, {}, Eigen::Vector3d::Zero(), {}, "beam");
    expect_mode_invariants(modes);
    r.f[k] = modes.frequency_hz(6);  // after the six rigid-body modes
  }
  return r;
}

double report(const char* name, const Refinement& r) {
  const double p = observed_order(r.cells_across, r.f);
  const double ratio = static_cast<double>(r.cells_across[2]) / r.cells_across[1];
  const double extrapolated = r.f[2] - (r.f[1] - r.f[2]) / (std::pow(ratio, p) - 1.0);
  std::printf(
      "%s: f1 = %.8f, %.8f, %.8f Hz (%d, %d, %d cells across): observed order %.2f, "
      "finest relative error %.1e (Richardson)\n",
      name, r.f[0], r.f[1], r.f[2], r.cells_across[0], r.cells_across[1], r.cells_across[2], p,
      r.f[2] / extrapolated - 1);
  EXPECT_GT(r.f[0], r.f[1]) << name;  // conforming FE converge from above
  EXPECT_GT(r.f[1], r.f[2]) << name;
  return p;
}

TEST(BeamConvergence, Tri6FreeFreeReachesFourthOrder) {
  EXPECT_GT(report("2-D free-free", free_free_2d()), 4.0 - 0.3);
  report("2-D clamped (corner singularity, not asserted)", clamped_2d());
}

TEST(BeamConvergence, Tet10FreeFreeOrder) {
  EXPECT_GT(report("3-D free-free", free_free_3d()), 3.3);
}

// The elastic gate: L = 0.079 m, h = 0.005 m, E = 12 MPa, ρ = 1100 kg/m³, ν = 0.4, plane strain
// (thickness 1 m), clamped at its base. Euler–Bernoulli with E/(1 − ν²): f1 = 14.75 Hz.
struct Gate {
  mesh::StructureMesh mesh = mesh::structured_rectangle(0.079, 0.005, 40, 4);
  fem::ElasticModel model{{12e6, 0.4, 1100.0}, fem::PlaneAssumption::plane_strain, 1.0};
};

TEST(ElasticGate2D, FirstFrequencyMatchesEulerBernoulli) {
  const Gate g;
  const ModeSet modes = compute_modes(g.mesh, g.model, std::vector<std::string>{"xmin"},
                                      {5, {}, "gate"}, {}, Eigen::Vector3d::Zero(), {}, "gate");
  expect_mode_invariants(modes);
  const double e_plane = 12e6 / (1 - 0.4 * 0.4), h = 0.005, l = 0.079;
  const double f_eb = 1.87510407 * 1.87510407 / (2 * std::numbers::pi) *
                      std::sqrt(e_plane * h * h / 12.0 / 1100.0) / (l * l);
  std::printf("gate f1: FE %.4f Hz, Euler–Bernoulli %.4f Hz, rel. diff %+.2e\n",
              modes.frequency_hz(0), f_eb, modes.frequency_hz(0) / f_eb - 1);
  EXPECT_NEAR(f_eb, 14.75, 0.01);
  EXPECT_NEAR(modes.frequency_hz(0), f_eb, 2e-2 * f_eb);
}

TEST(ElasticGate2D, FiveModesReproduceTheStaticTipDeflection) {
  const Gate g;
  const fem::SystemMatrices system = fem::assemble(g.mesh, g.model, "gate");
  const std::vector<std::string> clamped{"xmin"};
  const fem::DofMap dofs = fem::DofMap::clamp_groups(g.mesh, clamped, "gate");
  const EigenSolution solution =
      solve_eigenproblem(dofs.reduce(system.stiffness), dofs.reduce(system.mass), {5, {}, "gate"});
  const ModeSet modes = build_mode_set(solution, system, dofs, g.mesh, Eigen::Vector3d::Zero());
  expect_mode_invariants(modes);
  const Eigen::VectorXd force = fem::nodal_force(g.mesh, "xmax", Eigen::Vector2d(0.0, 1.0));
  const Eigen::VectorXd exact = fem::solve_static(system, dofs, force);
  const Eigen::VectorXd modal = modal_static_response(modes, force);
  auto tip = [&](const Eigen::VectorXd& u) {
    double sum = 0.0;
    for (mesh::Index n : g.mesh.node_groups.at("xmax")) sum += u(2 * n + 1);
    return sum / static_cast<double>(g.mesh.node_groups.at("xmax").size());
  };
  std::printf("gate tip deflection under 1 N: K⁻¹f %.6e m, 5 modes %.6e m, rel. diff %+.2e\n",
              tip(exact), tip(modal), tip(modal) / tip(exact) - 1);
  EXPECT_NEAR(tip(modal), tip(exact), 5e-3 * std::abs(tip(exact)));
}

}  // namespace
}  // namespace hm::modal
