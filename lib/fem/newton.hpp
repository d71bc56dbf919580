#pragma once
// Newton's method for the nonlinear structure: the sparse solver of its Newton matrices, and the
// options and report of one Newton solve, shared by the static and the dynamic solves.
#include <functional>
#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mesh/types.hpp"

namespace hm::fem {

struct NewtonOptions {
  /// Converged when ‖r‖ ≤ tolerance·scale on the free DOFs, the scale being the largest of the
  /// force terms of the equation (internal, external, inertial) [1].
  double tolerance = 1e-10;
  /// Also converged when a Newton correction is below this fraction of the solution, ‖δx‖ ≤
  /// increment_tolerance·‖x‖: the residual of a stiff body stalls at round-off of its element
  /// forces (which cancel to a small net force) before it reaches `tolerance`.
  double increment_tolerance = 1e-10;
  int max_iterations = 30;
  /// Backtracking on ‖r‖ (halving the step up to 6 times) when a full step raises the residual
  /// or inverts an element.
  bool line_search = true;
};

struct NewtonReport {
  bool converged = false;
  int iterations = 0;
  int substeps = 1;             ///< of a time step split for Newton (dynamics only)
  double residual = 0.0;        ///< ‖r‖/scale at the end [1]
  double min_det_f = 1.0;       ///< smallest J of the last accepted state
  mesh::Index worst_cell = -1;  ///< a failed solve's cell of smallest J (−1: none)
  std::string failure;          ///< why it failed (empty when converged)
};

/// Factorises Newton matrices of one fixed sparsity pattern: the symbolic analysis once, a
/// numeric factorisation per matrix. Symmetric matrices go to CHOLMOD's supernodal LLᵀ, falling
/// back to LDLᵀ when not positive definite; unsymmetric ones (the energy-conserving tangent,
/// follower loads) to a sparse LU.
class TangentSolver {
 public:
  TangentSolver();
  ~TangentSolver();
  TangentSolver(TangentSolver&&) noexcept;
  TangentSolver& operator=(TangentSolver&&) noexcept;

  /// False when the matrix is singular (no factorisation succeeded).
  bool factorize(const Eigen::SparseMatrix<double>& matrix, bool symmetric);
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// One evaluation of the equations r(x) = 0 on the free DOFs.
struct NewtonSystem {
  Eigen::VectorXd residual;
  Eigen::SparseMatrix<double> jacobian;  ///< ∂r/∂x, only when asked for
  bool symmetric = true;
  double scale = 1.0;  ///< force scale of the equation (NewtonOptions::tolerance)
  double min_det_f = 1.0;
  mesh::Index worst_cell = -1;
};

/// r(x) and, when `jacobian` is set, ∂r/∂x.
using NewtonEquations = std::function<NewtonSystem(const Eigen::VectorXd& x, bool jacobian)>;

/// Newton iterations from `x` (updated in place to the last accepted iterate). A step that
/// inverts an element (J ≤ 0) or raises the residual is halved (line search); a solve that
/// cannot continue reports why instead of throwing.
NewtonReport newton_solve(Eigen::VectorXd& x, const NewtonEquations& equations,
                          const NewtonOptions& options, TangentSolver& solver);

}  // namespace hm::fem
