#pragma once
// Interchangeable eigensolvers for K φ = λ M φ. ARPACK-ng (production) and Spectra run
// shift-invert Lanczos on the same ShiftInvertOperator; the dense solver (small models only)
// is the oracle both are checked against. None of them throws on non-convergence: the status,
// converged count and work done come back in EigenPairs (STYLE item 10).
#include <string>

#include <Eigen/Core>

#include "modal/eigen_operator.hpp"

namespace hm::modal {

enum class EigenStatus {
  converged,             ///< every requested pair converged
  not_converged,         ///< fewer pairs than requested converged (see `converged`)
  factorisation_failed,  ///< K − σM could not be factorised (σ an eigenvalue, K not PSD, ...)
  solver_error,          ///< the backend reported an error (`message`)
};

std::string to_string(EigenStatus s);

struct LanczosOptions {
  int subspace = 0;          ///< Lanczos basis size ncv; 0: max(2·nev + 1, 20), at most n
  int max_restarts = 1000;   ///< implicit restarts (ARPACK iparam[2], Spectra maxit)
  double tolerance = 1e-12;  ///< relative accuracy of the Ritz values of OP
  unsigned start_seed = 42;  ///< the starting vector is pseudo-random from this seed
};

/// Converged eigenpairs, λ ascending [rad²/s²]; vectors as the backend returns them (columns
/// M-orthonormal up to the solver tolerance), on the operator's DOFs.
struct EigenPairs {
  EigenStatus status = EigenStatus::solver_error;
  Eigen::VectorXd values;
  Eigen::MatrixXd vectors;
  int requested = 0;
  int converged = 0;
  int iterations = 0;       ///< restarts (Lanczos) or 1 (dense)
  int op_applications = 0;  ///< applications of (K − σM)⁻¹
  double seconds = 0.0;     ///< wall time of the iteration (excludes the factorisation)
  std::string message;
};

/// Lanczos subspace size for `nev` pairs of an n-DOF problem (nev < n required).
int subspace_size(const LanczosOptions& options, int nev, Eigen::Index n);

/// ARPACK-ng dsaupd/dseupd, bmat "G", which "LM", mode 3 (shift-invert). Needs 1 ≤ nev < n.
EigenPairs arpack_shift_invert(const ShiftInvertOperator& op, int nev,
                               const LanczosOptions& options = {});

/// Spectra SymGEigsShiftSolver (ShiftInvert mode) on the same operator. Needs 1 ≤ nev < n.
EigenPairs spectra_shift_invert(const ShiftInvertOperator& op, int nev,
                                const LanczosOptions& options = {});

/// Dense oracle (Eigen GeneralizedSelfAdjointEigenSolver): the nev lowest pairs. When K − σM is
/// positive definite it solves the inverted problem M x = ν (K − σM) x, whose backward error is
/// small relative to the low modes (the direct form K x = λ M x loses about λ_max/λ₁ in their
/// residuals); otherwise the direct form. O(n³): small models only. Needs 1 ≤ nev ≤ n.
EigenPairs dense_generalized(const SparseMatrix& stiffness, const SparseMatrix& mass, int nev,
                             double shift);

/// Deterministic starting vector shared by the Lanczos backends.
Eigen::VectorXd lanczos_start_vector(Eigen::Index n, unsigned seed);

}  // namespace hm::modal
