// tri6/tet10 shape functions and element matrices: interpolation, rigid-body null space,
// total mass, and exact strain energy of a linear displacement field (patch test).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "fem/elements.hpp"
#include "fem/material.hpp"

namespace hm::fem {
namespace {

// Reference node coordinates, gmsh order.
Eigen::MatrixXd reference_nodes(int dim) {
  if (dim == 2) {
    Eigen::MatrixXd x(6, 2);
    x << 0, 0, 1, 0, 0, 1, 0.5, 0, 0.5, 0.5, 0, 0.5;
    return x;
  }
  Eigen::MatrixXd x(10, 3);
  x << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1,  // corners
      0.5, 0, 0, 0.5, 0.5, 0, 0, 0.5, 0,    // e01 e12 e20
      0, 0, 0.5, 0, 0.5, 0.5, 0.5, 0, 0.5;  // e03 e23 e13
  return x;
}

ShapeValues shape(int dim, const Eigen::Vector3d& xi) {
  return dim == 2 ? tri6_shape(xi) : tet10_shape(xi);
}

/// A distorted straight-sided element: an affine map of the reference one.
Eigen::MatrixXd physical_nodes(int dim) {
  Eigen::MatrixXd a(dim, dim);
  if (dim == 2)
    a << 0.3, 0.05, -0.02, 0.2;
  else
    a << 0.3, 0.05, 0.01, -0.02, 0.2, 0.04, 0.03, -0.01, 0.25;
  const Eigen::VectorXd shift = Eigen::VectorXd::LinSpaced(dim, 1.0, 2.0);
  return (reference_nodes(dim) * a.transpose()).rowwise() + shift.transpose();
}

double measure(const Eigen::MatrixXd& nodes) {  // area (2-D) or volume (3-D)
  const int dim = static_cast<int>(nodes.cols());
  Eigen::MatrixXd edges(dim, dim);
  for (int k = 0; k < dim; ++k) edges.col(k) = (nodes.row(k + 1) - nodes.row(0)).transpose();
  return edges.determinant() / (dim == 2 ? 2.0 : 6.0);
}

ElasticModel rubber() {
  return {{12e6, 0.4, 1100.0}, PlaneAssumption::plane_strain, 0.7};
}

class ElementTest : public ::testing::TestWithParam<int> {};

TEST_P(ElementTest, ShapeFunctionsInterpolateAtNodes) {
  const int dim = GetParam();
  const Eigen::MatrixXd x = reference_nodes(dim);
  for (Eigen::Index b = 0; b < x.rows(); ++b) {
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    xi.head(dim) = x.row(b).transpose();
    const ShapeValues s = shape(dim, xi);
    for (Eigen::Index a = 0; a < x.rows(); ++a) EXPECT_NEAR(s.n(a), a == b ? 1.0 : 0.0, 1e-15);
  }
  const ShapeValues s = shape(dim, Eigen::Vector3d(0.2, 0.15, 0.1));
  EXPECT_NEAR(s.n.sum(), 1.0, 1e-15);
  // Σ_a x_a ∂N_a/∂ξ = I (the element reproduces linear fields).
  const Eigen::MatrixXd jac = x.transpose() * s.dn;
  EXPECT_LT((jac - Eigen::MatrixXd::Identity(dim, dim)).norm(), 1e-14);
}

TEST_P(ElementTest, StiffnessNullSpaceIsTheRigidMotions) {
  const int dim = GetParam();
  const ElasticModel model = rubber();
  const ElementMatrices e =
      element_matrices(physical_nodes(dim), elasticity_matrix(model, dim), 1100.0, 0.7);
  EXPECT_LT((e.stiffness - e.stiffness.transpose()).norm(), 1e-9 * e.stiffness.norm());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(e.stiffness);
  const int rigid = dim == 2 ? 3 : 6;
  const double largest = eig.eigenvalues().maxCoeff();
  for (int k = 0; k < rigid; ++k) EXPECT_LT(std::abs(eig.eigenvalues()(k)), 1e-12 * largest);
  EXPECT_GT(eig.eigenvalues()(rigid), 1e-6 * largest);  // no spurious zero-energy mode
}

TEST_P(ElementTest, ConsistentMassIntegratesDensity) {
  const int dim = GetParam();
  const Eigen::MatrixXd x = physical_nodes(dim);
  const double thickness = dim == 2 ? 0.7 : 1.0;
  const ElementMatrices e =
      element_matrices(x, elasticity_matrix(rubber(), dim), 1100.0, thickness);
  const double mass = 1100.0 * thickness * measure(x);
  for (int c = 0; c < dim; ++c) {
    Eigen::VectorXd t = Eigen::VectorXd::Zero(e.mass.rows());
    for (Eigen::Index a = 0; a < x.rows(); ++a) t(dim * a + c) = 1.0;
    EXPECT_NEAR(t.dot(e.mass * t), mass, 1e-13 * mass);
  }
  // Exact consistent mass of the corner–corner entry for straight-sided quadratic elements:
  // ∫ N_0² = A/30 (tri6) and V/70 (tet10) (Zienkiewicz).
  EXPECT_NEAR(e.mass(0, 0), mass * (dim == 2 ? 1.0 / 30.0 : 1.0 / 70.0), 1e-13 * mass);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(e.mass);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
}

TEST_P(ElementTest, LinearFieldHasExactStrainEnergy) {
  const int dim = GetParam();
  const Eigen::MatrixXd x = physical_nodes(dim);
  const ElasticModel model = rubber();
  const Eigen::MatrixXd d = elasticity_matrix(model, dim);
  const double thickness = dim == 2 ? 0.7 : 1.0;
  const ElementMatrices e = element_matrices(x, d, 1100.0, thickness);
  Eigen::MatrixXd grad(dim, dim);  // u = grad · x
  if (dim == 2)
    grad << 1e-3, 2e-4, -5e-4, 3e-4;
  else
    grad << 1e-3, 2e-4, 1e-4, -5e-4, 3e-4, 2e-4, 4e-4, -1e-4, -6e-4;
  Eigen::VectorXd u(dim * x.rows());
  for (Eigen::Index a = 0; a < x.rows(); ++a) u.segment(dim * a, dim) = grad * x.row(a).transpose();
  Eigen::VectorXd strain(dim == 2 ? 3 : 6);
  if (dim == 2)
    strain << grad(0, 0), grad(1, 1), grad(0, 1) + grad(1, 0);
  else
    strain << grad(0, 0), grad(1, 1), grad(2, 2), grad(1, 2) + grad(2, 1), grad(0, 2) + grad(2, 0),
        grad(0, 1) + grad(1, 0);
  const double exact = strain.dot(d * strain) * measure(x) * thickness;
  EXPECT_NEAR(u.dot(e.stiffness * u), exact, 1e-12 * exact);
}

INSTANTIATE_TEST_SUITE_P(Tri6AndTet10, ElementTest, ::testing::Values(2, 3),
                         [](const auto& p) { return p.param == 2 ? "tri6" : "tet10"; });

}  // namespace
}  // namespace hm::fem
