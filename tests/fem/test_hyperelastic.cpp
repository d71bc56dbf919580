// The hyperelastic laws and the total-Lagrangian body: stress and tangent against finite
// differences of the energy, the tangent of the body against central differences of its force,
// the linear limit (K(0) = K₀), objectivity under a 90° rigid rotation, and the modal-derivative
// right-hand side against differences of the tangent.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/hyperelastic.hpp"
#include "fem/hyperelastic_body.hpp"
#include "mesh/structured.hpp"

namespace hm::fem {
namespace {

const Material kRubber{12e6, 0.45, 1100.0};

HyperelasticModel model(MaterialLaw law, PlaneAssumption plane = PlaneAssumption::plane_strain,
                        double thickness = 0.1) {
  return {{kRubber, plane, thickness}, law};
}

/// The Green–Lagrange strain E = (FᵀF − I)/2 of a moderately large deformation (stretches
/// ~±20 %, a rotation of ~40°).
template <int D>
Eigen::Matrix<double, D, D> sample_e() {
  Eigen::Matrix<double, D, D> f = Eigen::Matrix<double, D, D>::Identity();
  f(0, 0) = 1.18;
  f(1, 1) = 0.87;
  f(0, 1) = 0.31;
  f(1, 0) = -0.22;
  if constexpr (D == 3) {
    f(2, 2) = 1.07;
    f(0, 2) = 0.12;
    f(2, 1) = -0.09;
  }
  return 0.5 * (f.transpose() * f - Eigen::Matrix<double, D, D>::Identity());
}

constexpr std::array<std::array<int, 2>, 6> kPairs3{
    {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
constexpr std::array<std::array<int, 2>, 3> kPairs2{{{0, 0}, {1, 1}, {0, 1}}};

template <int D>
std::array<int, 2> pair(int k) {
  return D == 2 ? kPairs2[static_cast<std::size_t>(k)] : kPairs3[static_cast<std::size_t>(k)];
}

/// E + h in the direction of engineering strain component k (E_IJ += h for I = J, E_IJ = E_JI
/// += h/2 for I ≠ J).
template <int D>
Eigen::Matrix<double, D, D> perturbed(const Eigen::Matrix<double, D, D>& e, int k, double h) {
  const auto [i, j] = pair<D>(k);
  Eigen::Matrix<double, D, D> out = e;
  if (i == j) {
    out(i, i) += h;
  } else {
    out(i, j) += 0.5 * h;
    out(j, i) += 0.5 * h;
  }
  return out;
}

template <int D>
void expect_law_consistent(const HyperelasticModel& m) {
  const Lame lame(m.elastic.material);
  const auto c = sample_e<D>();
  const MaterialPoint<D> p = evaluate_law<D>(m, lame, c);
  constexpr int V = D == 2 ? 3 : 6;
  const double h = 1e-6;
  for (int k = 0; k < V; ++k) {
    const auto [i, j] = pair<D>(k);
    // S_IJ = ∂W/∂E_IJ (engineering component: ∂W/∂γ = S_IJ for I ≠ J).
    const double dw = (strain_energy_density<D>(m, lame, perturbed<D>(c, k, h)) -
                       strain_energy_density<D>(m, lame, perturbed<D>(c, k, -h))) /
                      (2 * h);
    EXPECT_NEAR(dw, p.stress(i, j), 1e-6 * p.stress.norm()) << to_string(m.law) << " S" << k;
    const auto up = evaluate_law<D>(m, lame, perturbed<D>(c, k, h));
    const auto down = evaluate_law<D>(m, lame, perturbed<D>(c, k, -h));
    for (int r = 0; r < V; ++r) {
      const auto [a, b] = pair<D>(r);
      const double ds = (up.stress(a, b) - down.stress(a, b)) / (2 * h);
      EXPECT_NEAR(ds, p.tangent(r, k), 1e-6 * p.tangent.norm()) << to_string(m.law) << r << k;
    }
  }
}

TEST(HyperelasticLaw, StressAndTangentAreDerivativesOfTheEnergy) {
  for (MaterialLaw law : {MaterialLaw::saint_venant_kirchhoff, MaterialLaw::neo_hookean}) {
    expect_law_consistent<3>(model(law));
    expect_law_consistent<2>(model(law, PlaneAssumption::plane_strain));
    expect_law_consistent<2>(model(law, PlaneAssumption::plane_stress));
  }
}

TEST(HyperelasticLaw, SmallStrainLimitIsLinearElasticity) {
  for (MaterialLaw law : {MaterialLaw::saint_venant_kirchhoff, MaterialLaw::neo_hookean})
    for (PlaneAssumption plane : {PlaneAssumption::plane_strain, PlaneAssumption::plane_stress}) {
      const HyperelasticModel m = model(law, plane);
      const MaterialPoint<2> p =
          evaluate_law<2>(m, Lame(m.elastic.material), Eigen::Matrix2d::Zero());
      const Eigen::MatrixXd d = elasticity_matrix(m.elastic, 2);
      EXPECT_LT((p.tangent - d).norm(), 1e-12 * d.norm()) << to_string(law);
      EXPECT_LT(p.stress.norm(), 1e-6);
    }
}

TEST(HyperelasticLaw, NeoHookeanRefusesIncompressibleRatio) {
  HyperelasticModel m = model(MaterialLaw::neo_hookean);
  m.elastic.material.poisson_ratio = 0.5;
  try {
    validate(m, 2, "scene.toml: structure.material");
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("structure.material"), std::string::npos) << text;
    EXPECT_NE(text.find("ν = 0.5"), std::string::npos) << text;
    EXPECT_NE(text.find("neo-Hookean"), std::string::npos) << text;
  }
  EXPECT_THROW(material_law_from("mooney", "structure.material.law"), InputError);
}

/// A random displacement of amplitude `scale` [m] (deterministic).
Eigen::VectorXd random_field(Eigen::Index n, double scale, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  Eigen::VectorXd u(n);
  for (auto& x : u) x = scale * d(gen);
  return u;
}

/// A bending-like smooth field plus noise, large enough to rotate cells by ~0.3 rad.
Eigen::VectorXd smooth_field(const mesh::StructureMesh& m, double amplitude, unsigned seed) {
  Eigen::VectorXd u = random_field(m.dim * m.node_count(), 0.02 * amplitude, seed);
  for (Eigen::Index n = 0; n < m.node_count(); ++n) {
    const double x = m.nodes(n, 0);
    u[m.dim * n + 1] += amplitude * x * x;
    u[m.dim * n] -= 0.3 * amplitude * x * x * x;
  }
  return u;
}

double relative_tangent_error(const HyperelasticBody& body, const Eigen::VectorXd& u,
                              const EvaluationRequest& request, unsigned seed) {
  const Eigen::SparseMatrix<double> k = body.evaluate(u, request).tangent;
  const Eigen::VectorXd dir = random_field(u.size(), 1.0, seed);
  const double h = 1e-6 * u.cwiseAbs().maxCoeff();
  EvaluationRequest force_only = request;
  force_only.tangent = false;
  const Eigen::VectorXd up = u + h * dir, down = u - h * dir;
  const Eigen::VectorXd fd =
      (body.evaluate(up, force_only).force - body.evaluate(down, force_only).force) / (2 * h);
  const Eigen::VectorXd exact = k * dir;
  return (fd - exact).norm() / exact.norm();
}

TEST(HyperelasticBody, TangentMatchesCentralDifferences) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.2, 6, 2),
                                                mesh::structured_box(1.0, 0.2, 0.15, 4, 2, 1)};
  for (const auto& m : meshes)
    for (MaterialLaw law : {MaterialLaw::saint_venant_kirchhoff, MaterialLaw::neo_hookean})
      for (PlaneAssumption plane : {PlaneAssumption::plane_strain, PlaneAssumption::plane_stress}) {
        if (m.dim == 3 && plane == PlaneAssumption::plane_stress) continue;
        const HyperelasticBody body(m, model(law, plane), "test");
        const Eigen::VectorXd u = smooth_field(m, 0.3, 7);
        EXPECT_LT(relative_tangent_error(body, u, {true}, 11), 1e-6)
            << m.dim << "-D " << to_string(law);
      }
}

TEST(HyperelasticBody, EnergyConservingTangentMatchesCentralDifferencesForStvk) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.2, 6, 2);
  const HyperelasticBody body(m, model(MaterialLaw::saint_venant_kirchhoff), "test");
  const Eigen::VectorXd u0 = smooth_field(m, 0.2, 3), u1 = smooth_field(m, 0.3, 5);
  EvaluationRequest request;
  request.tangent = true;
  request.start = &u0;
  EXPECT_LT(relative_tangent_error(body, u1, request, 13), 1e-6);
}

TEST(HyperelasticBody, DiscreteGradientGivesTheExactEnergyDifference) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.2, 6, 2);
  for (MaterialLaw law : {MaterialLaw::saint_venant_kirchhoff, MaterialLaw::neo_hookean}) {
    const HyperelasticBody body(m, model(law), "test");
    const Eigen::VectorXd u0 = smooth_field(m, 0.2, 3), u1 = smooth_field(m, 0.3, 5);
    EvaluationRequest request;
    request.start = &u0;
    const double work = (u1 - u0).dot(body.evaluate(u1, request).force);
    const double difference = body.strain_energy(u1) - body.strain_energy(u0);
    EXPECT_NEAR(work, difference, 1e-10 * std::abs(difference)) << to_string(law);
  }
}

TEST(HyperelasticBody, ViscousTangentMatchesDifferencesInVelocity) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.2, 6, 2);
  const HyperelasticBody body(m, model(MaterialLaw::saint_venant_kirchhoff), "test");
  const Eigen::VectorXd u = smooth_field(m, 0.3, 7), v = random_field(u.size(), 1.0, 9);
  EvaluationRequest request;
  request.tangent = true;
  request.stiffness_weight = 0.0;
  request.damping_weight = 1.0;
  request.velocity = &v;
  request.beta = 0.01;
  const Eigen::SparseMatrix<double> c = body.evaluate(u, request).tangent;
  request.tangent = false;
  const Eigen::VectorXd f0 = body.evaluate(u, request).force;
  const Eigen::VectorXd dv = random_field(u.size(), 1.0, 21);
  const Eigen::VectorXd v2 = v + dv;
  request.velocity = &v2;
  // The viscous force is linear in the velocity: the difference is exact.
  const Eigen::VectorXd df = body.evaluate(u, request).force - f0;
  EXPECT_LT((df - c * dv).norm(), 1e-10 * df.norm());
}

TEST(HyperelasticBody, LinearLimitIsTheLinearModel) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.2, 6, 2),
                                                mesh::structured_box(1.0, 0.2, 0.15, 4, 2, 1)};
  for (const auto& m : meshes)
    for (const auto& [law, plane] :
         {std::pair{MaterialLaw::saint_venant_kirchhoff, PlaneAssumption::plane_strain},
          std::pair{MaterialLaw::neo_hookean, PlaneAssumption::plane_strain},
          std::pair{MaterialLaw::saint_venant_kirchhoff, PlaneAssumption::plane_stress}}) {
      const HyperelasticModel hm = model(law, plane);
      const HyperelasticBody body(m, hm, "test");
      const SystemMatrices linear = assemble(m, hm.elastic, "test");
      const Eigen::SparseMatrix<double> k0 =
          body.evaluate(Eigen::VectorXd::Zero(body.dof_count()), {true}).tangent;
      EXPECT_LT((k0 - linear.stiffness).norm(), 1e-12 * linear.stiffness.norm());
      // The body's stored K₀ (the modal derivatives' matrix) is the linear model's K.
      EXPECT_LT((body.linear_stiffness() - linear.stiffness).norm(),
                1e-12 * linear.stiffness.norm());
      EXPECT_EQ((body.mass() - linear.mass).norm(), 0.0);
      // f(εu) = ε K₀ u + O(ε²).
      const Eigen::VectorXd u = smooth_field(m, 1e-7, 5);
      const Eigen::VectorXd ku = linear.stiffness * u;
      EXPECT_LT((body.internal_force(u) - ku).norm(), 1e-5 * ku.norm()) << to_string(law);
    }
}

/// u = (R − I)(X − c) for a rotation by `angle` about z through c.
Eigen::VectorXd rigid_rotation(const mesh::StructureMesh& m, double angle) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::VectorXd u(m.dim * m.node_count());
  const Eigen::Vector3d c(0.3, 0.05, 0.0);
  for (Eigen::Index n = 0; n < m.node_count(); ++n) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x.head(m.dim) = m.nodes.row(n).transpose();
    u.segment(m.dim * n, m.dim) = ((r - Eigen::Matrix3d::Identity()) * (x - c)).head(m.dim);
  }
  return u;
}

TEST(HyperelasticBody, RigidRotationOfNinetyDegreesGivesNoForce) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.2, 6, 2),
                                                mesh::structured_box(1.0, 0.2, 0.15, 4, 2, 1)};
  for (const auto& m : meshes)
    for (MaterialLaw law : {MaterialLaw::saint_venant_kirchhoff, MaterialLaw::neo_hookean}) {
      const HyperelasticBody body(m, model(law), "test");
      const Eigen::VectorXd u = rigid_rotation(m, M_PI / 2);
      // Relative to the force the linear model gives the same displacement (spurious: K₀u ≠ 0).
      const double linear = (body.linear_stiffness() * u).norm();
      const double nonlinear = body.internal_force(u).norm();
      EXPECT_LT(nonlinear, 1e-10 * linear) << m.dim << "-D " << to_string(law);
      EXPECT_LT(std::abs(body.strain_energy(u)), 1e-10 * 0.5 * u.dot(body.linear_stiffness() * u));
      std::printf("[ objectivity ] %d-D %s: |f(u_rot90)| = %.3e N, linear |K0 u| = %.3e N\n", m.dim,
                  to_string(law), nonlinear, linear);
    }
}

TEST(HyperelasticBody, SecondDerivativeMatchesDifferencesOfTheTangent) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.2, 6, 2),
                                                mesh::structured_box(1.0, 0.2, 0.15, 4, 2, 1)};
  for (const auto& m : meshes) {
    const HyperelasticBody body(m, model(MaterialLaw::saint_venant_kirchhoff), "test");
    const Eigen::VectorXd a = random_field(body.dof_count(), 1.0, 1);
    const Eigen::VectorXd b = random_field(body.dof_count(), 1.0, 2);
    const double h = 1e-4;
    const Eigen::VectorXd up = h * b, down = -h * b;
    const Eigen::VectorXd fd =
        (body.evaluate(up, {true}).tangent * a - body.evaluate(down, {true}).tangent * a) / (2 * h);
    const Eigen::VectorXd exact = body.second_derivative(a, b);
    EXPECT_LT((fd - exact).norm(), 1e-7 * exact.norm()) << m.dim << "-D";
    EXPECT_LT((exact - body.second_derivative(b, a)).norm(), 1e-12 * exact.norm());
  }
}

TEST(HyperelasticBody, AllPairsOfSecondDerivativesInOnePassEqualThePairwiseOnes) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.2, 6, 2),
                                                mesh::structured_box(1.0, 0.2, 0.15, 4, 2, 1)};
  for (const auto& m : meshes) {
    const HyperelasticBody body(m, model(MaterialLaw::saint_venant_kirchhoff), "test");
    Eigen::MatrixXd directions(body.dof_count(), 3);
    for (int i = 0; i < 3; ++i)
      directions.col(i) = random_field(body.dof_count(), 1.0, static_cast<unsigned>(10 + i));
    const Eigen::MatrixXd all = body.second_derivatives(directions);
    ASSERT_EQ(all.cols(), 6);
    int column = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = i; j < 3; ++j, ++column) {
        const Eigen::VectorXd pair = body.second_derivative(directions.col(i), directions.col(j));
        EXPECT_LT((all.col(column) - pair).norm(), 1e-13 * pair.norm())
            << m.dim << "-D, pair " << i << ", " << j;
      }
  }
}

TEST(HyperelasticBody, GravityLoadIsTheWeight) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.2, 6, 2);
  const HyperelasticBody body(m, model(MaterialLaw::neo_hookean), "test");
  const Eigen::VectorXd f = body.body_force(Eigen::Vector2d(0.0, -9.81));
  double fy = 0.0;
  for (Eigen::Index n = 0; n < m.node_count(); ++n) fy += f[2 * n + 1];
  EXPECT_NEAR(fy, -9.81 * 1100.0 * 0.2 * 0.1, 1e-10);
}

}  // namespace
}  // namespace hm::fem
