// The reduced (modal) Saint Venant–Kirchhoff model: the basis (modes against a dense
// eigensolver, M-orthonormality, every modal derivative in its span), the reduced force, tangent
// and energy against the projected full ones in plane strain, plane stress and 3-D, the tangent
// against differences of the force, and then the reduced model against closed forms and the full
// model: the elastica under an end moment and Turek–Hron CSM1 against basis size, a CSM3-like
// release against the full dynamics, energy conservation over 100 periods, the energy balance
// of generalised-α and of Rayleigh damping, the interface Jacobian against differences, and the
// cost of the tensors and of a step.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>

#include "core/errors.hpp"
#include "fem/dof_map.hpp"
#include "fem/nonlinear_dynamics.hpp"
#include "fem/nonlinear_static.hpp"
#include "fem/reduced_basis.hpp"
#include "fem/reduced_dynamics.hpp"
#include "fem/reduced_static.hpp"
#include "fem/reduced_stvk.hpp"
#include "nonlinear_cases.hpp"

namespace hm::fem {
namespace {

using test::nearest_node;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A body clamped on its xmin side.
struct Clamped {
  mesh::StructureMesh mesh;
  HyperelasticBody body;
  DofMap dofs;
  Clamped(mesh::StructureMesh m, const HyperelasticModel& model)
      : mesh(std::move(m)),
        body(mesh, model, "test"),
        dofs(DofMap::clamp_groups(mesh, std::vector<std::string>{"xmin"}, "test")) {}
};

HyperelasticModel rubber(PlaneAssumption plane = PlaneAssumption::plane_strain) {
  return {{{12e6, 0.45, 1100.0}, plane, 0.1}, MaterialLaw::saint_venant_kirchhoff};
}

/// Reduced coordinates of a random state (fixed seed): normal entries weighted by 1/√(K1_ii),
/// an equal share of strain energy per basis vector, scaled so that max |V q| = `amplitude` [m].
Eigen::VectorXd random_state(const ReducedStvk& model, double amplitude, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd q(model.size());
  for (Eigen::Index i = 0; i < q.size(); ++i)
    q[i] = normal(generator) / std::sqrt(model.linear_stiffness()(i, i));
  return q * (amplitude / model.displacement(q).cwiseAbs().maxCoeff());
}

// ---------------------------------------------------------------------------------------------
// The basis

TEST(ReducedBasis, ModesMatchADenseEigensolverAndTheBasisIsMOrthonormal) {
  const Clamped c(mesh::structured_rectangle(1.0, 0.1, 12, 2), rubber());
  const LinearModes modes = lowest_modes(c.body, c.dofs, 6, "test");
  const Eigen::MatrixXd k = Eigen::MatrixXd(c.dofs.reduce(c.body.linear_stiffness()));
  const Eigen::MatrixXd m = Eigen::MatrixXd(c.dofs.reduce(c.body.mass()));
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> dense(k, m);
  for (int i = 0; i < 6; ++i) {
    // Against the Rayleigh quotient of the dense eigenvector: the dense eigenvalue itself carries
    // an absolute error ~ε·λ_max, 5e-10 of λ₁ here.
    const Eigen::VectorXd x = dense.eigenvectors().col(i);
    const Eigen::VectorXd phi = c.dofs.free_values(modes.shapes.col(i));
    const double rayleigh = x.dot(k * x) / x.dot(m * x);
    EXPECT_NEAR(modes.eigenvalues[i], rayleigh, 1e-10 * rayleigh);
    EXPECT_NEAR(modes.eigenvalues[i], dense.eigenvalues()[i], 1e-8 * rayleigh);
    // Both M-normalised: |cos| of their M-angle is 1 − (angle²)/2, the angle ≲ the tolerance 1e-6.
    EXPECT_NEAR(std::abs(x.dot(m * phi)) / std::sqrt(x.dot(m * x)), 1.0, 1e-11) << "mode " << i;
  }
  std::printf("[ basis ] 6 modes in %d subspace iterations, f1 = %.4f Hz\n", modes.iterations,
              std::sqrt(modes.eigenvalues[0]) / (2 * M_PI));

  const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, modes, {6, true, -1}, "test");
  const Eigen::MatrixXd& v = basis.vectors;
  EXPECT_EQ(basis.mode_count, 6);
  EXPECT_EQ(basis.mode_count + basis.derivative_count + basis.dropped, 6 + 21);
  const Eigen::Index r = basis.size();
  EXPECT_LT((v.transpose() * (c.body.mass() * v) - Eigen::MatrixXd::Identity(r, r)).norm(), 1e-12);
  for (Eigen::Index dof = 0; dof < v.rows(); ++dof)
    if (c.dofs.is_clamped(dof)) {
      EXPECT_EQ(v.row(dof).norm(), 0.0);
    }
  // Every θ_ij = −K₀⁻¹ d²f[φ_i, φ_j] lies in span(V): its M-orthogonal remainder vanishes.
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> k0(
      c.dofs.reduce(c.body.linear_stiffness()));
  double worst = 0.0;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) {
      const Eigen::VectorXd theta = c.dofs.full_values(k0.solve(
          -c.dofs.free_values(c.body.second_derivative(modes.shapes.col(i), modes.shapes.col(j)))));
      const Eigen::VectorXd rest = theta - v * (v.transpose() * (c.body.mass() * theta));
      worst = std::max(
          worst, std::sqrt(rest.dot(c.body.mass() * rest) / theta.dot(c.body.mass() * theta)));
    }
  std::printf("[ basis ] 6 modes + derivatives: r = %ld (%d dropped); worst remainder %.2e\n",
              static_cast<long>(r), basis.dropped, worst);
  EXPECT_LT(worst, 1e-6);  // the drop tolerance: a dropped θ is in the span to that

  // Derivatives of the first 2 modes only: θ_00, θ_01, θ_11 after the 6 modes.
  const ReducedBasis few = build_reduced_basis(c.body, c.dofs, modes, {6, true, 2}, "test");
  EXPECT_EQ(few.size(), 9);
  EXPECT_EQ(few.derivative_count, 3);
  EXPECT_EQ((few.origin.back()), (std::array<int, 2>{1, 1}));
}

TEST(ReducedBasis, InvalidOptionsAreInputErrors) {
  const Clamped c(mesh::structured_rectangle(1.0, 0.1, 4, 1), rubber());
  EXPECT_THROW(build_reduced_basis(c.body, c.dofs, {0, true, -1}, "structure.basis"), InputError);
  EXPECT_THROW(build_reduced_basis(c.body, c.dofs, {3, true, 4}, "structure.basis"), InputError);
  try {
    lowest_modes(c.body, c.dofs, 100000, "structure.modes");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("structure.modes"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------
// The reduced tensors against the projected full model

struct ProjectionErrors {
  double force = 0.0, tangent = 0.0, energy = 0.0;
  double min_det_f = 1.0;  ///< how far the states go: the smallest J = det F
};

/// Relative errors of f_r, K_r, W against Vᵀf(Vq), VᵀK(Vq)V, W(Vq), worst of three random states
/// with max |u| = 10 % of the length (rotations of ~15°, local J down to 0.46).
/// (At 15 % one plane-stress state stretches a point to E11 + E22 = 0.94, beyond (λ + 2μ)/2λ =
/// 0.61 at ν = 0.45, where StVK's plane-stress E33 = −λ(E11 + E22)/(λ + 2μ) would make the
/// thickness C33 = 1 + 2E33 ≤ 0: the full model keeps C33 > 0 there and so leaves StVK, the
/// reduced polynomial does not — 20 % apart in force. Strains of 60 % are outside StVK's use.)
ProjectionErrors projection_errors(const HyperelasticBody& body, const ReducedStvk& model) {
  ProjectionErrors worst;
  const Eigen::MatrixXd& v = model.basis();
  for (unsigned seed : {1u, 2u, 3u}) {
    const Eigen::VectorXd q = random_state(model, 0.10, seed);
    const BodyEvaluation full = body.evaluate(v * q, {true});
    worst.min_det_f = std::min(worst.min_det_f, full.min_det_f);
    const Eigen::VectorXd f = v.transpose() * full.force;
    const Eigen::MatrixXd k = v.transpose() * (full.tangent * v);
    const ReducedEvaluation reduced = model.evaluate(q, true);
    worst.force = std::max(worst.force, (reduced.force - f).norm() / f.norm());
    worst.tangent = std::max(worst.tangent, (reduced.tangent - k).norm() / k.norm());
    worst.energy = std::max(
        worst.energy, std::abs(reduced.strain_energy - full.strain_energy) / full.strain_energy);
  }
  return worst;
}

TEST(ReducedStvk, ForceTangentAndEnergyEqualTheProjectedFullOnes) {
  struct Case {
    const char* name;
    mesh::StructureMesh mesh;
    HyperelasticModel model;
  };
  const std::vector<Case> cases{
      {"2-D plane strain", mesh::structured_rectangle(1.0, 0.1, 10, 2), rubber()},
      {"2-D plane stress", mesh::structured_rectangle(1.0, 0.1, 10, 2),
       rubber(PlaneAssumption::plane_stress)},
      {"3-D", mesh::structured_box(1.0, 0.2, 0.2, 6, 2, 2), rubber()}};
  for (const Case& k : cases) {
    const Clamped c(k.mesh, k.model);
    const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, {4, true, -1}, "test");
    const ReducedStvk model(c.body, basis.vectors, "test");
    const ProjectionErrors e = projection_errors(c.body, model);
    std::printf(
        "[ projection ] %s, r = %ld: force %.2e, tangent %.2e, energy %.2e (relative), smallest "
        "J %.2f; tensors %.3f s\n",
        k.name, static_cast<long>(model.size()), e.force, e.tangent, e.energy, e.min_det_f,
        model.setup_seconds());
    EXPECT_LT(e.force, 1e-10) << k.name;
    EXPECT_LT(e.tangent, 1e-10) << k.name;
    EXPECT_LT(e.energy, 1e-10) << k.name;
    EXPECT_LT((model.linear_stiffness() -
               basis.vectors.transpose() * (c.body.linear_stiffness() * basis.vectors))
                  .norm(),
              1e-10 * model.linear_stiffness().norm());
  }
}

/// For a cubic f_r the Richardson combination (4 D(h) − D(2h))/3 of central differences D is
/// exact: what is left is round-off.
TEST(ReducedStvk, TangentMatchesDifferencesOfTheForce) {
  const Clamped c(mesh::structured_rectangle(1.0, 0.1, 10, 2), rubber());
  const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, {4, true, -1}, "test");
  const ReducedStvk model(c.body, basis.vectors, "test");
  const Eigen::VectorXd q = random_state(model, 0.15, 5);
  const Eigen::VectorXd dq = random_state(model, 1.0, 6);
  auto central = [&](double h) {
    return Eigen::VectorXd((model.force(q + h * dq) - model.force(q - h * dq)) / (2 * h));
  };
  const double h = 1e-3 * q.norm() / dq.norm();
  const Eigen::VectorXd exact = model.tangent(q) * dq;
  const double plain = (central(h) - exact).norm() / exact.norm();
  const double richardson = ((4 * central(h) - central(2 * h)) / 3 - exact).norm() / exact.norm();
  std::printf("[ tangent ] central differences %.2e, Richardson %.2e (relative)\n", plain,
              richardson);
  EXPECT_LT(plain, 1e-5);
  EXPECT_LT(richardson, 1e-9);
}

TEST(ReducedStvk, RefusesTheNeoHookeanLaw) {
  HyperelasticModel model = rubber();
  model.law = MaterialLaw::neo_hookean;
  const Clamped c(mesh::structured_rectangle(1.0, 0.1, 4, 1), model);
  try {
    ReducedStvk reduced(c.body, Eigen::MatrixXd::Ones(c.body.dof_count(), 2), "structure 'gate'");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("structure 'gate'"), std::string::npos) << text;
    EXPECT_NE(text.find("saint_venant_kirchhoff"), std::string::npos) << text;
  }
}

// ---------------------------------------------------------------------------------------------
// The reduced model against closed forms and the full model

struct Tip {
  double ux = 0.0, uy = 0.0;
};

Tip tip_of(const mesh::StructureMesh& m, const Eigen::VectorXd& u, const Eigen::Vector2d& at) {
  const Eigen::Index node = nearest_node(m, at);
  return {u[2 * node], u[2 * node + 1]};
}

/// The elastica strip: L = 1 m, h = 0.01 m, E = 1 GPa, ν = 0.3, plane strain, 100 × 2 cells,
/// clamped at x = 0, the follower end moment M = θ EI/L.
struct Elastica {
  static constexpr double kTheta = 1.0;
  Clamped c{mesh::structured_rectangle(1.0, 0.01, 100, 2),
            {{{1e9, 0.3, 1000.0}, PlaneAssumption::plane_strain, 1.0},
             MaterialLaw::saint_venant_kirchhoff}};
  test::FollowerMoment moment{c.mesh, "xmax", kTheta * 1e9 / (1 - 0.09) * 1e-6 / 12.0, 1.0};
  StaticLoad load;
  Elastica() {
    load.follower = [this](const Eigen::VectorXd& u) { return moment.force(u); };
    load.follower_stiffness = [this](const Eigen::VectorXd& u) { return moment.stiffness(u); };
  }
  Tip tip(const Eigen::VectorXd& u) const { return tip_of(c.mesh, u, {1.0, 0.005}); }
  /// Relative errors against the closed form, transverse L(1 − cos θ)/θ, axial L(1 − sin θ/θ).
  static Tip error(const Tip& t) {
    const double uy = (1 - std::cos(kTheta)) / kTheta, ux = -(1 - std::sin(kTheta) / kTheta);
    return {std::abs(t.ux / ux - 1), std::abs(t.uy / uy - 1)};
  }
};

double distance(const Tip& a, const Tip& b) {
  return std::hypot(a.ux - b.ux, a.uy - b.uy);
}

/// The reduced model's error against basis size, the elastica at θ = 1 rad (tip error: the
/// distance of the reduced tip from the closed form's, per L; "vs full": against the full model
/// on the same mesh, whose own tip is 3.1e-4 L from the closed form). Measured:
///   basis                  r  dropped | tip error | uy err   ux err  | vs full uy, ux
///   8 modes alone          8     0    | 4.8e-1    | 9.8e-1   1.0e+0  | −98 %, −100 %  (locked)
///   2 modes + derivatives  5     0    | 3.5e-2    | 5.0e-2   1.7e-1  | −5.0 %, −17 %
///   4 modes + derivatives 14     0    | 2.6e-3    | 5.1e-3   6.4e-3  | +0.57 %, +0.74 %
///   6 modes + derivatives 26     1    | 1.5e-3    | 3.0e-3   4.4e-3  | +0.36 %, +0.54 %
///   8 modes + derivatives 41     3    | 1.3e-3    | 2.3e-3   4.5e-3  | +0.29 %, +0.55 %
/// (10 and 12 modes with derivatives, r = 56 and 71: +0.28 / +0.25 % in uy, +0.54 / +0.49 % in
/// ux — a linear subspace converges slowly at a rotation of 1 rad: the axial field must follow
/// −½∫w′² closely, or the spurious membrane strain, 12 L²/h² = 1.2e5 times stiffer than bending,
/// holds the strip. Linear modes alone lock completely.)
TEST(ReducedStatic, ElasticaErrorDecreasesWithBasisSize) {
  Elastica e;
  const double uy = (1 - std::cos(Elastica::kTheta)) / Elastica::kTheta;
  const Tip exact{-(1 - std::sin(Elastica::kTheta) / Elastica::kTheta), uy};
  const Tip full = e.tip(solve_static(e.c.body, e.c.dofs, e.load, {}, "elastica").u);
  std::printf("[ elastica ] full model, %ld DOFs: tip error %.2e (uy %.2e, ux %.2e)\n",
              static_cast<long>(e.c.dofs.free_count()), distance(full, exact),
              Elastica::error(full).uy, Elastica::error(full).ux);
  const LinearModes modes = lowest_modes(e.c.body, e.c.dofs, 8, "elastica");
  std::printf(
      "[ elastica ] modes derivatives   r dropped | tip error  uy error  ux error | vs full uy   "
      "ux     | tensors  Newton\n");
  double previous = 1e300;
  for (int n : {8, 2, 4, 6, 8}) {
    const bool derivatives = previous < 1e300;  // the first row: 8 modes alone
    const ReducedBasis basis =
        build_reduced_basis(e.c.body, e.c.dofs, modes, {n, derivatives, -1}, "elastica");
    const ReducedStvk model(e.c.body, basis.vectors, "elastica");
    const ReducedStaticResult r =
        solve_reduced_static(model, project(model, e.load), {}, "elastica");
    const Tip tip = e.tip(model.displacement(r.q));
    const Tip error = Elastica::error(tip);
    const double tip_error = distance(tip, exact);
    std::printf(
        "[ elastica ] %5d %11s %3ld %7d | %8.2e  %8.2e  %8.2e | %+6.2f %% %+6.2f %% | %6.3f s  "
        "%6d\n",
        n, derivatives ? "all" : "none", static_cast<long>(basis.size()), basis.dropped, tip_error,
        error.uy, error.ux, 100 * (tip.uy / full.uy - 1), 100 * (tip.ux / full.ux - 1),
        model.setup_seconds(), r.newton_iterations);
    if (!derivatives) {
      EXPECT_GT(error.uy, 0.9);  // linear modes alone lock
      previous = tip_error;
      continue;
    }
    EXPECT_LT(tip_error, previous) << n << " modes";
    previous = tip_error;
    if (n == 8) {
      EXPECT_LT(std::abs(tip.uy / full.uy - 1), 0.004);
      EXPECT_LT(std::abs(tip.ux / full.ux - 1), 0.006);
    }
  }
}

/// Turek–Hron CSM1 (flag 40 × 4 cells, StVK plane strain, g = 2 m/s² down) against the
/// benchmark (ux −7.187 mm, uy −66.10 mm) and the full model on the same mesh. Measured (full
/// model: ux −7.1362 mm, −0.71 %; uy −65.835 mm, −0.40 %):
///   modes + derivatives   r | ux vs ref, vs full | uy vs ref, vs full | tip from the full's
///   1                     2 | +3.17 %, +3.90 %   | +0.44 %, +0.84 %   | 9.4e-3
///   2                     5 | −0.88 %, −0.17 %   | −0.53 %, −0.13 %   | 1.3e-3
///   4                    14 | −0.70 %, +0.01 %   | −0.40 %, +0.00 %   | 1.8e-5
///   6                    27 | −0.71 %, −0.00 %   | −0.40 %, −0.00 %   | 1.2e-6
///   8                    44 | −0.71 %, −0.00 %   | −0.40 %, −0.00 %   | 2.2e-6
/// (the last column per the tip deflection). The tip turns ~0.25 rad (4δ/3L of a linear
/// cantilever), and 4 modes with their derivatives already give the full model's answer; 1 mode
/// and its derivative overshoot ux by 4 %.
TEST(ReducedStatic, TurekHronCsm1AgainstBasisSize) {
  const Clamped c(test::turek_hron_flag(40, 4), test::turek_hron_material());
  StaticLoad load;
  load.dead = c.body.body_force(Eigen::Vector2d(0.0, -2.0));
  const Eigen::Vector2d at(0.6, 0.2);
  const Tip full = tip_of(c.mesh, solve_static(c.body, c.dofs, load, {}, "csm1").u, at);
  const Tip reference{-7.187e-3, -66.10e-3};
  std::printf("[ CSM1 ] full model: ux %.4f mm (%+.2f %%), uy %.3f mm (%+.2f %%)\n", 1e3 * full.ux,
              100 * (full.ux / reference.ux - 1), 1e3 * full.uy,
              100 * (full.uy / reference.uy - 1));
  const LinearModes modes = lowest_modes(c.body, c.dofs, 8, "csm1");
  std::printf(
      "[ CSM1 ] modes   r | ux [mm]  vs ref   vs full | uy [mm]  vs ref   vs full | from full\n");
  double previous = 1e300;
  for (int n : {1, 2, 4, 6, 8}) {
    const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, modes, {n, true, -1}, "csm1");
    const ReducedStvk model(c.body, basis.vectors, "csm1");
    const ReducedStaticResult r = solve_reduced_static(model, project(model, load), {}, "csm1");
    const Tip tip = tip_of(c.mesh, model.displacement(r.q), at);
    // The distance of the tip from the full model's, per the full model's tip deflection.
    const double error = distance(tip, full) / std::hypot(full.ux, full.uy);
    std::printf(
        "[ CSM1 ] %5d %3ld | %7.4f  %+6.2f %%  %+6.2f %% | %7.3f  %+6.2f %%  %+6.2f %% | %.2e\n", n,
        static_cast<long>(basis.size()), 1e3 * tip.ux, 100 * (tip.ux / reference.ux - 1),
        100 * (tip.ux / full.ux - 1), 1e3 * tip.uy, 100 * (tip.uy / reference.uy - 1),
        100 * (tip.uy / full.uy - 1), error);
    // Down to the floor of the basis tolerances (modes and drop tolerance 1e-6), then within it.
    if (previous > 1e-5) {
      EXPECT_LT(error, previous) << n << " modes";
    } else {
      EXPECT_LT(error, 1e-5) << n << " modes";
    }
    previous = error;
  }
}

// ---------------------------------------------------------------------------------------------
// Dynamics

struct Trajectory {
  std::vector<Tip> tip;
  double seconds_per_step = 0.0;
  int newton = 0;  ///< iterations summed over the steps
};

/// The flag released from rest under gravity, 40 × 4 cells, Δt = 5 ms for `steps` steps: the full
/// model.
Trajectory full_release(const Clamped& c, const DynamicsOptions& options, int steps, double dt) {
  NonlinearDynamics dyn(c.body, c.dofs, options);
  const Eigen::VectorXd weight = c.body.body_force(Eigen::Vector2d(0.0, -2.0));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(c.body.dof_count());
  dyn.start(0.0, zero, zero, weight);
  Trajectory out;
  const auto begin = std::chrono::steady_clock::now();
  for (int n = 1; n <= steps; ++n) {
    const NewtonReport& report = dyn.solve_step(dt, weight);
    EXPECT_TRUE(report.converged) << "full, step " << n << ": " << report.failure;
    if (!report.converged) break;
    out.newton += report.iterations;
    dyn.commit();
    out.tip.push_back(tip_of(c.mesh, dyn.state().u, {0.6, 0.2}));
  }
  out.seconds_per_step = seconds_since(begin) / steps;
  return out;
}

/// The same release in the reduced model.
Trajectory reduced_release(const Clamped& c, const ReducedStvk& model,
                           const DynamicsOptions& options, int steps, double dt) {
  ReducedDynamics dyn(model, options);
  const Eigen::VectorXd weight = model.project(c.body.body_force(Eigen::Vector2d(0.0, -2.0)));
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.size());
  dyn.start(0.0, zero, zero, weight);
  Trajectory out;
  const auto begin = std::chrono::steady_clock::now();
  for (int n = 1; n <= steps; ++n) {
    const NewtonReport& report = dyn.solve_step(dt, weight);
    EXPECT_TRUE(report.converged) << "reduced, step " << n << ": " << report.failure;
    if (!report.converged) break;
    out.newton += report.iterations;
    dyn.commit();
    out.tip.push_back(tip_of(c.mesh, model.displacement(dyn.state().q), {0.6, 0.2}));
  }
  out.seconds_per_step = seconds_since(begin) / steps;
  return out;
}

/// The largest distance between two tip histories, per the largest tip displacement of `b`.
double trajectory_error(const Trajectory& a, const Trajectory& b) {
  double worst = 0.0, size = 0.0;
  for (std::size_t n = 0; n < std::min(a.tip.size(), b.tip.size()); ++n) {
    worst = std::max(worst, distance(a.tip[n], b.tip[n]));
    size = std::max(size, std::hypot(b.tip[n].ux, b.tip[n].uy));
  }
  return worst / size;
}

/// CSM3-like: the Turek–Hron flag released under gravity, 1 s (about one period) at Δt = 5 ms,
/// generalised-α ρ∞ = 0.8 in both models — the reduced scheme is the full one restricted to
/// span(V), so the difference is the basis alone. Also the cost of a step and of the tensors.
/// Measured (ci build, one thread; the full model: 1440 DOFs, 31–41 ms and 3.7 Newton a step):
///   modes + derivatives   r | tip error over 1 s | tensors | step     | speed-up
///   1                     2 | 1.8e-1             | 0.000 s | 0.02 ms  | ~1500 x
///   2                     5 | 2.4e-3             | 0.001 s | 0.02 ms  | ~1500 x
///   4                    14 | 2.5e-4             | 0.004 s | 0.10 ms  |  ~350 x
///   6                    27 | 5.9e-5             | 0.10 s  | 0.65 ms  |   ~55 x
///   8                    44 | 2.5e-5             | 0.41 s  | 2.2 ms   |   ~15 x
/// (the error: the largest distance between the tips over the second, per the largest tip
/// displacement; 3.0 Newton iterations a reduced step). The cubic tensor's r·r(r+1)(r+2)/6
/// coefficients make a step cost ~r⁴: past ~30 vectors the reduced model loses its edge on a 2-D
/// mesh of this size.
TEST(ReducedDynamics, ReleaseFollowsTheFullModelAsTheBasisGrows) {
  const Clamped c(test::turek_hron_flag(40, 4), test::turek_hron_material());
  const DynamicsOptions options;
  const int steps = 200;
  const double dt = 0.005;
  const Trajectory full = full_release(c, options, steps, dt);
  std::printf("[ release ] full model, %ld DOFs: %.2f ms a step, %.1f Newton a step\n",
              static_cast<long>(c.dofs.free_count()), 1e3 * full.seconds_per_step,
              full.newton / double(steps));
  const LinearModes modes = lowest_modes(c.body, c.dofs, 8, "release");
  std::printf(
      "[ release ] modes   r | tip error over 1 s | tensors    step      Newton  speed-up\n");
  double previous = 1e300;
  for (int n : {1, 2, 4, 6, 8}) {
    const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, modes, {n, true, -1}, "release");
    const ReducedStvk model(c.body, basis.vectors, "release");
    const Trajectory reduced = reduced_release(c, model, options, steps, dt);
    const double error = trajectory_error(reduced, full);
    std::printf("[ release ] %5d %3ld | %18.2e | %6.3f s  %6.3f ms  %5.1f  %6.0f x\n", n,
                static_cast<long>(model.size()), error, model.setup_seconds(),
                1e3 * reduced.seconds_per_step, reduced.newton / double(steps),
                full.seconds_per_step / reduced.seconds_per_step);
    if (previous > 1e-5) {
      EXPECT_LT(error, previous) << n << " modes";
    } else {
      EXPECT_LT(error, 1e-5) << n << " modes";
    }
    previous = error;
  }
}

/// The cantilever of the full model's energy tests: 1 × 0.1 m, E = 10 MPa, 12 × 2 cells, bent by
/// a tip load of 3 kN to a tip deflection of ~25 % of its length (the reduced static solution),
/// then released; 4 modes with their derivatives.
struct Release {
  Clamped c{mesh::structured_rectangle(1.0, 0.1, 12, 2),
            {{{1e7, 0.3, 1000.0}, PlaneAssumption::plane_strain, 1.0},
             MaterialLaw::saint_venant_kirchhoff}};
  ReducedStvk model{c.body, build_reduced_basis(c.body, c.dofs, {4, true, -1}, "release").vectors,
                    "release"};
  Eigen::VectorXd q0, zero = Eigen::VectorXd::Zero(model.size());
  double period = 0.0;  ///< first-mode period of the linear beam [s]

  Release() {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(c.body.dof_count());
    f[2 * nearest_node(c.mesh, Eigen::Vector2d(1.0, 0.05)) + 1] = 3.0e3;
    q0 = solve_reduced_static(model, {model.project(f), {}, {}}, {}, "release").q;
    const double ei = 1e7 / (1 - 0.09) * 1e-3 / 12, mu = 1000 * 0.1;
    period = 2 * M_PI / (1.8751 * 1.8751 * std::sqrt(ei / mu));
  }
};

TEST(ReducedDynamics, EnergyConservingSchemeKeepsTheEnergyOver100Periods) {
  Release r;
  EXPECT_GT(r.model.displacement(r.q0).cwiseAbs().maxCoeff(), 0.2);  // a large deflection
  DynamicsOptions options;
  options.scheme = TimeScheme::energy_conserving;
  options.newton.tolerance = 1e-12;
  ReducedDynamics dyn(r.model, options);
  dyn.start(0.0, r.q0, r.zero, r.zero);
  const double e0 = dyn.energy().kinetic + dyn.energy().strain;
  double worst = 0.0, max_kinetic = 0.0;
  int iterations = 0;
  const auto begin = std::chrono::steady_clock::now();
  for (int n = 0; n < 100 * 20; ++n) {
    const NewtonReport& report = dyn.solve_step(r.period / 20, r.zero);
    ASSERT_TRUE(report.converged) << "step " << n << ": " << report.failure;
    iterations += report.iterations;
    dyn.commit();
    worst = std::max(worst, std::abs((dyn.energy().kinetic + dyn.energy().strain) / e0 - 1));
    max_kinetic = std::max(max_kinetic, dyn.energy().kinetic);
  }
  std::printf(
      "[ energy ] reduced (r = %ld), 100 periods at 20 steps: max |E/E0 - 1| = %.2e, %.1f Newton "
      "a step, %.3f ms a step\n",
      static_cast<long>(r.model.size()), worst, iterations / 2000.0,
      1e3 * seconds_since(begin) / 2000);
  EXPECT_LT(worst, 1e-6);
  EXPECT_GT(max_kinetic, 0.5 * e0);  // it really swings
  EXPECT_LT(std::abs(dyn.energy().numerical_dissipation), 1e-6 * e0);
}

/// Generalised-α takes energy at the rate its ρ∞ sets, and books it as numerical dissipation.
TEST(ReducedDynamics, GeneralisedAlphaDissipationIsBooked) {
  Release r;
  double previous_loss = 0.0;
  for (double rho : {0.9, 0.6, 0.3}) {
    DynamicsOptions options;
    options.rho_infinity = rho;
    ReducedDynamics dyn(r.model, options);
    dyn.start(0.0, r.q0, r.zero, r.zero);
    const double e0 = dyn.energy().kinetic + dyn.energy().strain;
    for (int n = 0; n < 6 * 40; ++n) {
      ASSERT_TRUE(dyn.solve_step(r.period / 40, r.zero).converged) << "ρ∞ " << rho;
      dyn.commit();
    }
    const double loss = 1 - (dyn.energy().kinetic + dyn.energy().strain) / e0;
    std::printf("[ generalised-alpha ] reduced, rho_inf = %.1f: energy lost over 6 periods %.3e\n",
                rho, loss);
    EXPECT_NEAR(dyn.energy().numerical_dissipation / e0, loss, 1e-9);
    EXPECT_GT(loss, previous_loss) << "ρ∞ " << rho;
    previous_loss = loss;
  }
}

TEST(ReducedDynamics, RayleighDampingEnergyIsAccountedFor) {
  Release r;
  DynamicsOptions options;
  options.scheme = TimeScheme::energy_conserving;
  options.rayleigh_alpha = 0.5;
  options.rayleigh_beta = 1e-3;
  options.newton.tolerance = 1e-12;
  ReducedDynamics dyn(r.model, options);
  dyn.start(0.0, r.q0, r.zero, r.zero);
  const double e0 = dyn.energy().kinetic + dyn.energy().strain;
  for (int n = 0; n < 200; ++n) {
    ASSERT_TRUE(dyn.solve_step(r.period / 20, r.zero).converged);
    dyn.commit();
  }
  const EnergyBalance& e = dyn.energy();
  std::printf("[ damping ] reduced: damped %.3f of E0, numerical dissipation %.2e of E0\n",
              e.damping / e0, e.numerical_dissipation / e0);
  EXPECT_GT(e.damping, 0.1 * e0);
  EXPECT_LT(std::abs(e.numerical_dissipation), 1e-7 * e0);  // the midpoint balance is exact
}

/// A run restored from its state after 10 steps continues exactly as the uninterrupted one.
TEST(ReducedDynamics, RestoredRunContinuesTheUninterruptedOne) {
  Release r;
  for (TimeScheme scheme : {TimeScheme::generalized_alpha, TimeScheme::energy_conserving}) {
    DynamicsOptions options;
    options.scheme = scheme;
    options.rayleigh_alpha = 0.1;
    ReducedDynamics whole(r.model, options), restored(r.model, options);
    whole.start(0.0, r.q0, r.zero, r.zero);
    const double dt = r.period / 20;
    for (int n = 0; n < 20; ++n) {
      ASSERT_TRUE(whole.solve_step(dt, r.zero).converged);
      whole.commit();
      if (n == 9) {
        const ReducedState& s = whole.state();
        restored.restore(s.time, s.q, s.v, s.a, s.load, whole.energy(), whole.start_energy());
      }
      if (n >= 10) {
        ASSERT_TRUE(restored.solve_step(dt, r.zero).converged);
        restored.commit();
      }
    }
    EXPECT_EQ(restored.state().q, whole.state().q) << to_string(scheme);
    EXPECT_EQ(restored.state().v, whole.state().v) << to_string(scheme);
    EXPECT_NEAR(restored.energy().numerical_dissipation, whole.energy().numerical_dissipation,
                1e-14 * whole.start_energy())
        << to_string(scheme);
    EXPECT_NEAR(restored.energy().damping, whole.energy().damping, 1e-14 * whole.start_energy());
  }
}

/// dā/dF_end against central differences of the trial's mean acceleration in the end load, in
/// the middle of a swing, for both schemes.
TEST(ReducedDynamics, MeanAccelerationResponseMatchesDifferences) {
  Release r;
  for (TimeScheme scheme : {TimeScheme::generalized_alpha, TimeScheme::energy_conserving}) {
    DynamicsOptions options;
    options.scheme = scheme;
    options.newton.tolerance = 1e-13;
    ReducedDynamics dyn(r.model, options);
    dyn.start(0.0, r.q0, r.zero, r.zero);
    const double dt = r.period / 40;
    for (int n = 0; n < 7; ++n) {
      ASSERT_TRUE(dyn.solve_step(dt, r.zero).converged);
      dyn.commit();
    }
    auto mean_acceleration = [&](const Eigen::VectorXd& load) {
      EXPECT_TRUE(dyn.solve_step(dt, load).converged);
      return Eigen::VectorXd((dyn.trial().v - dyn.state().v) / dt);
    };
    ASSERT_TRUE(dyn.solve_step(dt, r.zero).converged);
    const Eigen::MatrixXd exact = dyn.mean_acceleration_response();
    const double h = 1e-4 * dyn.state().internal.norm();
    Eigen::MatrixXd differences(r.model.size(), r.model.size());
    for (Eigen::Index k = 0; k < r.model.size(); ++k) {
      const Eigen::VectorXd e = h * Eigen::VectorXd::Unit(r.model.size(), k);
      differences.col(k) = (mean_acceleration(e) - mean_acceleration(-e)) / (2 * h);
    }
    const double error = (differences - exact).norm() / exact.norm();
    std::printf("[ interface ] %s: |dā/dF - differences| = %.2e (relative)\n", to_string(scheme),
                error);
    EXPECT_LT(error, 1e-6) << to_string(scheme);
  }
}

/// The cost in 3-D, where a reduced model pays most (not asserted): a box beam 1 × 0.1 × 0.1 m
/// (E = 2 GPa, ρ = 1000 kg/m³) of 16 × 2 × 2 cells (384 tet10) released under gravity, 20 steps
/// of 2 ms of the full model and of the reduced one with 2, 4, 6 modes and their derivatives.
/// Measured: full 2400 DOFs, 91 ms a step; r = 5 / 14 / 27: tensors 0.002 / 0.016 / 0.13 s, a
/// step 0.012 / 0.056 / 0.39 ms (7000 / 1600 / 230 x); the tip error after 40 ms 21 / 0.62 /
/// 0.15 % (an early transient, rich in the higher modes).
TEST(ReducedDynamics, CostOfTensorsAndStepsIn3D) {
  const Clamped c(mesh::structured_box(1.0, 0.1, 0.1, 16, 2, 2),
                  {{{2e9, 0.3, 1000.0}, PlaneAssumption::plane_strain, 1.0},
                   MaterialLaw::saint_venant_kirchhoff});
  const DynamicsOptions options;
  const int steps = 20;
  const double dt = 0.002;
  const Eigen::Vector3d g(0.0, -9.81, 0.0);
  NonlinearDynamics full(c.body, c.dofs, options);
  const Eigen::VectorXd weight = c.body.body_force(g);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(c.body.dof_count());
  full.start(0.0, zero, zero, weight);
  auto begin = std::chrono::steady_clock::now();
  for (int n = 0; n < steps; ++n) {
    ASSERT_TRUE(full.solve_step(dt, weight).converged);
    full.commit();
  }
  const double full_step = seconds_since(begin) / steps;
  const Eigen::Index tip = nearest_node(c.mesh, Eigen::Vector3d(1.0, 0.05, 0.05));
  const double full_tip = full.state().u[3 * tip + 1];
  std::printf("[ cost 3-D ] full model, %ld DOFs: %.1f ms a step; tip uy %.3f mm after %d steps\n",
              static_cast<long>(c.dofs.free_count()), 1e3 * full_step, 1e3 * full_tip, steps);
  begin = std::chrono::steady_clock::now();
  const LinearModes modes = lowest_modes(c.body, c.dofs, 6, "cost");
  std::printf("[ cost 3-D ] 6 modes: %.3f s\n", seconds_since(begin));
  std::printf("[ cost 3-D ] modes   r | basis    tensors  | step      speed-up | tip uy error\n");
  for (int n : {2, 4, 6}) {
    begin = std::chrono::steady_clock::now();
    const ReducedBasis basis = build_reduced_basis(c.body, c.dofs, modes, {n, true, -1}, "cost");
    const double basis_seconds = seconds_since(begin);
    const ReducedStvk model(c.body, basis.vectors, "cost");
    ReducedDynamics reduced(model, options);
    const Eigen::VectorXd q0 = Eigen::VectorXd::Zero(model.size());
    reduced.start(0.0, q0, q0, model.project(weight));
    begin = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      ASSERT_TRUE(reduced.solve_step(dt, model.project(weight)).converged);
      reduced.commit();
    }
    const double step = seconds_since(begin) / steps;
    const double reduced_tip = model.displacement(reduced.state().q)[3 * tip + 1];
    std::printf("[ cost 3-D ] %5d %3ld | %6.3f s  %6.3f s | %7.3f ms  %6.0f x | %.2e\n", n,
                static_cast<long>(model.size()), basis_seconds, model.setup_seconds(), 1e3 * step,
                full_step / step, std::abs(reduced_tip / full_tip - 1));
  }
}

}  // namespace
}  // namespace hm::fem
