#pragma once
// BiCGSTAB (van der Vorst 1992) for the row-scaled PPE, whose diagonal is 1: the Jacobi
// preconditioner is then the identity and the iteration is the plain one. Written here rather
// than taken from Eigen for one reason, measured: Eigen's BiCGSTAB runs its dot products and
// vector updates on one thread, so on the 2-D dam break (20 800 points, 243 iterations a step)
// the PPE solve ran only 1.45× faster on 2 threads. Here every loop of an iteration is one
// OpenMP loop (the sparse products fused with the dot products that follow them), with static
// schedules, so a run is reproducible for a given thread count.
#include <Eigen/SparseCore>

namespace hm::linsolve {

struct BicgstabResult {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  ///< ‖b − Ax‖ / ‖b‖ at the end (0 when b = 0)
};

/// Solves A x = b from the guess in x, until ‖b − Ax‖ ≤ tolerance·‖b‖ or max_iterations; the
/// shadow residual is restarted when it becomes orthogonal to the residual (as Eigen does).
BicgstabResult bicgstab(const Eigen::SparseMatrix<double, Eigen::RowMajor, int>& a,
                        const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                        int max_iterations);

}  // namespace hm::linsolve
