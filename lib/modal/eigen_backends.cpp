#include "modal/eigen_backends.hpp"

#include <algorithm>
#include <chrono>
#include <random>

#include <Eigen/Eigenvalues>

#include "core/errors.hpp"

namespace hm::modal {

std::string to_string(EigenStatus s) {
  switch (s) {
    case EigenStatus::converged:
      return "converged";
    case EigenStatus::not_converged:
      return "not_converged";
    case EigenStatus::factorisation_failed:
      return "factorisation_failed";
    case EigenStatus::solver_error:
      return "solver_error";
  }
  return "unknown";
}

int subspace_size(const LanczosOptions& options, int nev, Eigen::Index n) {
  const int wanted = options.subspace > 0 ? options.subspace : std::max(2 * nev + 1, 20);
  return static_cast<int>(std::min<Eigen::Index>(std::max(wanted, nev + 1), n));
}

Eigen::VectorXd lanczos_start_vector(Eigen::Index n, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v(i) = uniform(generator);
  return v;
}

EigenPairs dense_generalized(const SparseMatrix& stiffness, const SparseMatrix& mass, int nev,
                             double shift) {
  HM_ASSERT(nev >= 1 && nev <= stiffness.rows(), "dense solver needs 1 ≤ nev ≤ n; nev = {}, n = {}",
            nev, stiffness.rows());
  const auto start = std::chrono::steady_clock::now();
  const Eigen::MatrixXd k(stiffness), m(mass);
  const Eigen::MatrixXd shifted = k - shift * m;
  EigenPairs out;
  out.requested = nev;
  out.iterations = 1;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  const bool inverted = Eigen::LLT<Eigen::MatrixXd>(shifted).info() == Eigen::Success;
  if (inverted)  // M x = ν (K − σM) x, ν = 1/(λ − σ): the low modes come out accurately
    solver.compute(m, shifted, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  else
    solver.compute(k, m, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  if (solver.info() != Eigen::Success) {
    out.status = EigenStatus::solver_error;
    out.message = "dense generalised eigensolver failed (is M positive definite?)";
  } else if (inverted) {
    // ν descending ↔ λ ascending (all ν > 0 since K − σM and M are positive definite).
    out.values = (1.0 / solver.eigenvalues().reverse().head(nev).array() + shift).matrix();
    out.vectors = solver.eigenvectors().rowwise().reverse().leftCols(nev);
    out.converged = nev;
    out.status = EigenStatus::converged;
  } else {
    out.values = solver.eigenvalues().head(nev);
    out.vectors = solver.eigenvectors().leftCols(nev);
    out.converged = nev;
    out.status = EigenStatus::converged;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hm::modal
