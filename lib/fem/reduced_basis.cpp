#include "fem/reduced_basis.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Eigen/CholmodSupport>
#include <Eigen/Eigenvalues>

#include "core/errors.hpp"

namespace hm::fem {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;
using Cholesky = Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower>;

/// LLᵀ of K₀ on the free DOFs; NumericalError naming `context` when K₀ is not positive definite.
void factorize_stiffness(Cholesky& llt, const SparseMatrix& k, std::string_view context) {
  llt.cholmod().print = 0;
  llt.compute(k);
  if (llt.info() != Eigen::Success)
    numerical_error(
        "{}: the linear stiffness K₀ on the free DOFs is not positive definite (is the body "
        "clamped?)",
        context);
}

/// A reproducible random start block (n × columns, entries in [−1, 1]).
Eigen::MatrixXd start_block(Eigen::Index n, Eigen::Index columns) {
  std::mt19937_64 generator(20240611);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::MatrixXd x(n, columns);
  for (Eigen::Index j = 0; j < columns; ++j)
    for (Eigen::Index i = 0; i < n; ++i) x(i, j) = uniform(generator);
  return x;
}

/// Makes the entry of largest magnitude of every column positive.
void fix_signs(Eigen::MatrixXd& x) {
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    Eigen::Index at = 0;
    x.col(j).cwiseAbs().maxCoeff(&at);
    if (x(at, j) < 0.0) x.col(j) *= -1.0;
  }
}

/// One Rayleigh–Ritz projection on span(y): Ritz values ascending and vectors z (zᵀYᵀMYz = I).
Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> rayleigh_ritz(const Eigen::MatrixXd& y,
                                                                        const Eigen::MatrixXd& ky,
                                                                        const Eigen::MatrixXd& my) {
  const Eigen::MatrixXd kr = 0.5 * (y.transpose() * ky + ky.transpose() * y);
  const Eigen::MatrixXd mr = 0.5 * (y.transpose() * my + my.transpose() * y);
  return Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd>(kr, mr);
}

/// The largest residual of inverse iteration ‖λ y − x‖_M/‖x‖_M, y = K⁻¹Mx, of the first `count`
/// columns of x (M-orthonormal Ritz vectors with Ritz values λ); the λ are accurate to about its
/// square. (‖Kx − λMx‖/‖Kx‖ weighs the error in x by the stiffness and stalls far higher.)
double worst_residual(const Eigen::MatrixXd& x, const Eigen::MatrixXd& mx, const Eigen::MatrixXd& y,
                      const Eigen::MatrixXd& my, const Eigen::VectorXd& lambda, int count) {
  double worst = 0.0;
  for (int i = 0; i < count; ++i) {
    const Eigen::VectorXd r = lambda[i] * y.col(i) - x.col(i);
    const Eigen::VectorXd mr = lambda[i] * my.col(i) - mx.col(i);
    worst = std::max(worst, std::sqrt(std::max(0.0, r.dot(mr)) / x.col(i).dot(mx.col(i))));
  }
  return worst;
}

/// An M-orthonormal set built one candidate at a time (modified Gram–Schmidt, twice).
class MOrthonormalSet {
 public:
  MOrthonormalSet(const SparseMatrix& mass, Eigen::Index capacity)
      : mass_(mass), v_(mass.rows(), capacity), mv_(mass.rows(), capacity) {}

  /// Appends the part of `x` M-orthogonal to the set, normalised; false (and nothing appended)
  /// when that part's M-norm is below `tolerance` of x's.
  bool append(Eigen::VectorXd x, double tolerance) {
    const double norm0 = std::sqrt(x.dot(mass_ * x));
    for (int pass = 0; pass < 2; ++pass)
      for (Eigen::Index j = 0; j < count_; ++j) x -= mv_.col(j).dot(x) * v_.col(j);
    const Eigen::VectorXd mx = mass_ * x;
    const double norm = std::sqrt(x.dot(mx));
    if (!(norm > tolerance * norm0)) return false;
    v_.col(count_) = x / norm;
    mv_.col(count_) = mx / norm;
    ++count_;
    return true;
  }
  Eigen::MatrixXd vectors() const { return v_.leftCols(count_); }

 private:
  const SparseMatrix& mass_;
  Eigen::MatrixXd v_, mv_;
  Eigen::Index count_ = 0;
};

/// θ_ij = −K₀⁻¹ d²f[φ_i, φ_j] on the free DOFs for i ≤ j < k, in lexicographic order of (i, j).
Eigen::MatrixXd modal_derivatives(const HyperelasticBody& body, const DofMap& dofs,
                                  const Cholesky& llt, const Eigen::MatrixXd& modes, int k,
                                  std::vector<std::array<int, 2>>& pairs) {
  const Eigen::MatrixXd rhs = -dofs.reduce(body.second_derivatives(modes.leftCols(k)));
  for (int i = 0; i < k; ++i)
    for (int j = i; j < k; ++j) pairs.push_back({i, j});
  return llt.solve(rhs);
}

}  // namespace

LinearModes lowest_modes(const HyperelasticBody& body, const DofMap& dofs, int count,
                         std::string_view context, double tolerance) {
  const Eigen::Index n = dofs.free_count();
  if (count < 1 || count > n)
    input_error("{}: {} modes requested; allowed: 1 to {} (the free DOFs)", context, count, n);
  const SparseMatrix k = dofs.reduce(body.linear_stiffness());
  const SparseMatrix m = dofs.reduce(body.mass());
  Cholesky llt;
  factorize_stiffness(llt, k, context);
  const Eigen::Index block = std::min<Eigen::Index>(n, std::max(2 * count, count + 8));
  Eigen::MatrixXd x = start_block(n, block);
  Eigen::VectorXd lambda;
  constexpr int kMaxIterations = 300;
  double residual = 0.0;
  for (int iteration = 0; iteration <= kMaxIterations; ++iteration) {
    const Eigen::MatrixXd mx = m * x;
    Eigen::MatrixXd y = llt.solve(mx);
    Eigen::MatrixXd my = m * y;
    if (iteration > 0) {  // x, λ: the Ritz pairs of the last iteration
      residual = worst_residual(x, mx, y, my, lambda, count);
      if (residual <= tolerance) {
        LinearModes out;
        Eigen::MatrixXd shapes = x.leftCols(count);
        fix_signs(shapes);
        out.shapes = dofs.expand(shapes);
        out.eigenvalues = lambda.head(count);
        out.iterations = iteration;
        return out;
      }
    }
    // Scale the columns to unit M-norm: their sizes differ by the ratios of the λ.
    const Eigen::VectorXd norms = (y.cwiseProduct(my)).colwise().sum().cwiseSqrt().transpose();
    y = y * norms.cwiseInverse().asDiagonal();
    my = my * norms.cwiseInverse().asDiagonal();
    const auto ritz = rayleigh_ritz(y, Eigen::MatrixXd(k * y), my);
    x = y * ritz.eigenvectors();
    lambda = ritz.eigenvalues();
  }
  numerical_error("{}: the subspace iteration for {} modes stopped at residual {:.3e} > {:.1e}",
                  context, count, residual, tolerance);
}

void validate(const BasisOptions& o, std::string_view context) {
  if (o.modes < 1) input_error("{}: {} modes is invalid; at least 1", context, o.modes);
  if (o.derivative_modes < -1 || o.derivative_modes > o.modes)
    input_error("{}: derivatives of the first {} modes is invalid; allowed: -1 (all) to {}",
                context, o.derivative_modes, o.modes);
  if (!(o.drop_tolerance > 0.0 && o.drop_tolerance < 1.0))
    input_error("{}: drop tolerance {} is invalid; it must lie in (0, 1)", context,
                o.drop_tolerance);
}

ReducedBasis build_reduced_basis(const HyperelasticBody& body, const DofMap& dofs,
                                 const LinearModes& modes, const BasisOptions& options,
                                 std::string_view context) {
  validate(options, context);
  if (modes.shapes.cols() < options.modes || modes.shapes.rows() != body.dof_count())
    input_error("{}: {} modes of {} DOFs given; {} modes of {} DOFs needed", context,
                modes.shapes.cols(), modes.shapes.rows(), options.modes, body.dof_count());
  const Eigen::MatrixXd phi = modes.shapes.leftCols(options.modes);
  const int k = !options.derivatives           ? 0
                : options.derivative_modes < 0 ? options.modes
                                               : options.derivative_modes;
  std::vector<std::array<int, 2>> pairs;
  Eigen::MatrixXd theta(dofs.free_count(), 0);
  if (k > 0) {
    Cholesky llt;
    factorize_stiffness(llt, dofs.reduce(body.linear_stiffness()), context);
    theta = modal_derivatives(body, dofs, llt, phi, k, pairs);
  }
  const SparseMatrix m = dofs.reduce(body.mass());
  MOrthonormalSet set(m, options.modes + theta.cols());
  ReducedBasis out;
  for (int i = 0; i < options.modes; ++i) {
    if (set.append(dofs.free_values(phi.col(i)), options.drop_tolerance)) {
      out.origin.push_back({i, -1});
      ++out.mode_count;
    } else {
      ++out.dropped;
    }
  }
  for (Eigen::Index c = 0; c < theta.cols(); ++c) {
    if (set.append(theta.col(c), options.drop_tolerance)) {
      out.origin.push_back(pairs[static_cast<std::size_t>(c)]);
      ++out.derivative_count;
    } else {
      ++out.dropped;
    }
  }
  out.vectors = dofs.expand(set.vectors());
  out.eigenvalues = modes.eigenvalues.head(options.modes);
  return out;
}

ReducedBasis build_reduced_basis(const HyperelasticBody& body, const DofMap& dofs,
                                 const BasisOptions& options, std::string_view context) {
  validate(options, context);
  return build_reduced_basis(body, dofs, lowest_modes(body, dofs, options.modes, context), options,
                             context);
}

}  // namespace hm::fem
