#include "fem/elements.hpp"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

#include <Eigen/LU>

#include "core/errors.hpp"
#include "fem/quadrature.hpp"

namespace hm::fem {
namespace {

constexpr std::array<std::pair<int, int>, 3> kTri6Edges{{{0, 1}, {1, 2}, {2, 0}}};
constexpr std::array<std::pair<int, int>, 6> kTet10Edges{
    {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}}};

/// Quadratic shape functions from barycentric coordinates L = (1 − Σξ, ξ, η[, ζ]):
/// corners L_i(2L_i − 1), mid-edge nodes 4 L_a L_b.
template <std::size_t NEdges>
ShapeValues quadratic_shape(const Eigen::Vector3d& xi, int dim,
                            const std::array<std::pair<int, int>, NEdges>& edges) {
  const int corners = dim + 1;
  Eigen::VectorXd l(corners);
  l(0) = 1.0;
  for (int k = 0; k < dim; ++k) {  // element-wise: GCC 12 misreads a dynamic-size head() copy
    l(k + 1) = xi(k);
    l(0) -= xi(k);
  }
  // dL_m/dξ_k: row 0 is −1, rows 1..dim the identity.
  Eigen::MatrixXd dl(corners, dim);
  dl.row(0).setConstant(-1.0);
  dl.bottomRows(dim).setIdentity();

  const int nodes = corners + static_cast<int>(NEdges);
  ShapeValues s{Eigen::VectorXd(nodes), Eigen::MatrixXd(nodes, dim)};
  for (int i = 0; i < corners; ++i) {
    s.n(i) = l(i) * (2.0 * l(i) - 1.0);
    s.dn.row(i) = (4.0 * l(i) - 1.0) * dl.row(i);
  }
  for (std::size_t e = 0; e < NEdges; ++e) {
    const auto [a, b] = edges[e];
    const int node = corners + static_cast<int>(e);
    s.n(node) = 4.0 * l(a) * l(b);
    s.dn.row(node) = 4.0 * (l(b) * dl.row(a) + l(a) * dl.row(b));
  }
  return s;
}

/// Strain–displacement matrix (Voigt, engineering shear) from physical gradients (nodes × dim).
Eigen::MatrixXd strain_matrix(const Eigen::MatrixXd& grad) {
  const int dim = static_cast<int>(grad.cols());
  const Eigen::Index nodes = grad.rows();
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(dim == 3 ? 6 : 3, dim * nodes);
  for (Eigen::Index a = 0; a < nodes; ++a) {
    const Eigen::Index c = dim * a;
    const double gx = grad(a, 0), gy = grad(a, 1);
    if (dim == 2) {
      b(0, c) = gx;
      b(1, c + 1) = gy;
      b(2, c) = gy;
      b(2, c + 1) = gx;
      continue;
    }
    const double gz = grad(a, 2);
    b(0, c) = gx;
    b(1, c + 1) = gy;
    b(2, c + 2) = gz;
    b(3, c + 1) = gz;
    b(3, c + 2) = gy;
    b(4, c) = gz;
    b(4, c + 2) = gx;
    b(5, c) = gy;
    b(5, c + 1) = gx;
  }
  return b;
}

ShapeValues shape(int dim, const Eigen::Vector3d& xi) {
  return dim == 2 ? tri6_shape(xi) : tet10_shape(xi);
}

const QuadratureRule& rule(int dim, int degree) {
  return dim == 2 ? triangle_rule(degree) : tetrahedron_rule(degree);
}

void add_stiffness(const Eigen::MatrixXd& coords, const Eigen::MatrixXd& elasticity,
                   double thickness, ElementMatrices& out) {
  const int dim = static_cast<int>(coords.cols());
  const QuadratureRule& q = rule(dim, 2);
  for (std::size_t p = 0; p < q.points.size(); ++p) {
    const ShapeValues s = shape(dim, q.points[p]);
    const Eigen::MatrixXd jac = coords.transpose() * s.dn;  // ∂x_i/∂ξ_j
    const double det = jac.determinant();
    out.min_jacobian = std::min(out.min_jacobian, det);
    const Eigen::MatrixXd grad = s.dn * jac.inverse();
    const Eigen::MatrixXd b = strain_matrix(grad);
    out.stiffness.noalias() += (q.weights[p] * det * thickness) * b.transpose() * elasticity * b;
  }
}

void add_mass(const Eigen::MatrixXd& coords, double density, double thickness,
              ElementMatrices& out) {
  const int dim = static_cast<int>(coords.cols());
  const QuadratureRule& q = rule(dim, 4);
  const Eigen::Index nodes = coords.rows();
  Eigen::MatrixXd scalar_mass = Eigen::MatrixXd::Zero(nodes, nodes);
  for (std::size_t p = 0; p < q.points.size(); ++p) {
    const ShapeValues s = shape(dim, q.points[p]);
    const double det = (coords.transpose() * s.dn).determinant();
    out.min_jacobian = std::min(out.min_jacobian, det);
    scalar_mass.noalias() += (q.weights[p] * det * density * thickness) * s.n * s.n.transpose();
  }
  for (Eigen::Index a = 0; a < nodes; ++a)
    for (Eigen::Index b = 0; b < nodes; ++b)
      for (int c = 0; c < dim; ++c) out.mass(dim * a + c, dim * b + c) = scalar_mass(a, b);
}

}  // namespace

ShapeValues tri6_shape(const Eigen::Vector3d& xi) {
  return quadratic_shape(xi, 2, kTri6Edges);
}

ShapeValues tet10_shape(const Eigen::Vector3d& xi) {
  return quadratic_shape(xi, 3, kTet10Edges);
}

ElementMatrices element_matrices(const Eigen::MatrixXd& coords, const Eigen::MatrixXd& elasticity,
                                 double density, double thickness) {
  const int dim = static_cast<int>(coords.cols());
  HM_ASSERT((dim == 2 && coords.rows() == 6) || (dim == 3 && coords.rows() == 10),
            "element with {} nodes in {}-D is neither tri6 nor tet10", coords.rows(), dim);
  const Eigen::Index n = dim * coords.rows();
  ElementMatrices out{Eigen::MatrixXd::Zero(n, n), Eigen::MatrixXd::Zero(n, n),
                      std::numeric_limits<double>::infinity()};
  add_stiffness(coords, elasticity, thickness, out);
  add_mass(coords, density, thickness, out);
  return out;
}

}  // namespace hm::fem
