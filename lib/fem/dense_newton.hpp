#pragma once
// Newton's method on a small dense system (the reduced structure models: r unknowns, r ≲ 100),
// with the options, report and line search of the sparse solve (fem/newton.hpp): converged when
// ‖r‖ ≤ tolerance·scale or a correction is below increment_tolerance·‖x‖; for a symmetric
// Jacobian the step is shortened where the slope δᵀr(x + sδ) changes sign. The Jacobian is
// factorised by LU with partial pivoting; a reciprocal condition number below 1e-14 counts as
// singular. There are no elements here, so min_det_f and worst_cell stay at their defaults.
#include <functional>

#include <Eigen/Core>

#include "fem/newton.hpp"

namespace hm::fem {

/// One evaluation of the equations r(x) = 0.
struct DenseSystem {
  Eigen::VectorXd residual;
  Eigen::MatrixXd jacobian;  ///< ∂r/∂x, only when asked for
  bool symmetric = true;
  double scale = 1.0;  ///< force scale of the equation (NewtonOptions::tolerance)
};

using DenseEquations = std::function<DenseSystem(const Eigen::VectorXd& x, bool jacobian)>;

/// Newton iterations from `x` (updated in place to the last accepted iterate). A solve that
/// cannot continue reports why instead of throwing.
NewtonReport dense_newton_solve(Eigen::VectorXd& x, const DenseEquations& equations,
                                const NewtonOptions& options);

}  // namespace hm::fem
