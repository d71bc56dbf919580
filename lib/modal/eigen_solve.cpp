#include "modal/eigen_solve.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/errors.hpp"

namespace hm::modal {
namespace {

void validate(const ModeRequest& request, Eigen::Index free_dofs) {
  const bool by_count = request.count != 0;
  const bool by_frequency = request.max_frequency_hz.has_value();
  if (by_count == by_frequency)
    input_error("{}: request either a number of modes or a maximum frequency, not {}",
                request.context, by_count ? "both" : "neither");
  if (by_count && request.count < 0)
    input_error("{}: number of modes = {}; it must be ≥ 1", request.context, request.count);
  if (by_count && request.count > free_dofs)
    input_error(
        "{}: {} modes requested, but the structure has only {} free DOFs; request at "
        "most {} modes",
        request.context, request.count, free_dofs, free_dofs);
  if (by_frequency && !(*request.max_frequency_hz > 0.0))
    input_error("{}: maximum frequency = {} Hz; it must be > 0", request.context,
                *request.max_frequency_hz);
}

double eigenvalue_of(double frequency_hz) {
  const double omega = 2.0 * std::numbers::pi * frequency_hz;
  return omega * omega;
}

/// One run of the chosen backend for nev pairs; dense when Lanczos cannot hold a basis.
EigenPairs run_backend(EigenBackend backend, const SparseMatrix& k, const SparseMatrix& m,
                       const ShiftInvertOperator& op, int nev, const LanczosOptions& lanczos) {
  if (backend == EigenBackend::dense || nev + 1 >= k.rows())
    return dense_generalized(k, m, nev, op.shift());
  if (backend == EigenBackend::spectra) return spectra_shift_invert(op, nev, lanczos);
  return arpack_shift_invert(op, nev, lanczos);
}

void accumulate(EigenPairs& total, const EigenPairs& run) {
  const int iterations = total.iterations + run.iterations;
  const int applications = total.op_applications + run.op_applications;
  const double seconds = total.seconds + run.seconds;
  total = run;
  total.iterations = iterations;
  total.op_applications = applications;
  total.seconds = seconds;
}

/// Keeps the pairs with λ ≤ lambda_max.
void truncate(EigenPairs& pairs, double lambda_max) {
  int keep = 0;
  while (keep < pairs.values.size() && pairs.values(keep) <= lambda_max) ++keep;
  pairs.values.conservativeResize(keep);
  pairs.vectors.conservativeResize(Eigen::NoChange, keep);
  pairs.converged = keep;
  pairs.requested = keep;
}

}  // namespace

std::string to_string(EigenBackend b) {
  switch (b) {
    case EigenBackend::arpack:
      return "arpack";
    case EigenBackend::spectra:
      return "spectra";
    case EigenBackend::dense:
      return "dense";
  }
  return "unknown";
}

double default_shift(const SparseMatrix& stiffness, const SparseMatrix& mass) {
  return -1e-8 * stiffness.diagonal().sum() / mass.diagonal().sum();
}

EigenSolution solve_eigenproblem(const SparseMatrix& stiffness, const SparseMatrix& mass,
                                 const ModeRequest& request, const EigenOptions& options) {
  const Eigen::Index n = stiffness.rows();
  validate(request, n);
  EigenSolution solution;
  solution.backend = options.backend;
  solution.shift = options.shift.value_or(default_shift(stiffness, mass));
  const SparseShiftInvert op(stiffness, mass, solution.shift, options.factorisation);
  solution.factorisation = op.factorisation();
  solution.factorisation_seconds = op.factorisation_seconds();
  if (!op.ok() && options.backend != EigenBackend::dense) {
    solution.pairs.status = EigenStatus::factorisation_failed;
    solution.pairs.requested = request.count;
    solution.pairs.message = fmt::format(
        "{}: K − σM with σ = {} rad²/s² could not be factorised ({}); σ may be an eigenvalue or "
        "K not positive semi-definite",
        request.context, solution.shift, to_string(op.factorisation()));
    return solution;
  }
  if (!request.max_frequency_hz) {
    solution.pairs =
        run_backend(options.backend, stiffness, mass, op, request.count, options.lanczos);
    solution.solves = 1;
    return solution;
  }
  const double lambda_max = eigenvalue_of(*request.max_frequency_hz);
  int nev = static_cast<int>(std::min<Eigen::Index>(std::max(options.first_block, 1), n));
  while (true) {
    accumulate(solution.pairs,
               run_backend(options.backend, stiffness, mass, op, nev, options.lanczos));
    ++solution.solves;
    if (solution.pairs.status != EigenStatus::converged) return solution;
    if (solution.pairs.values(solution.pairs.converged - 1) > lambda_max || nev == n) break;
    nev = static_cast<int>(std::min<Eigen::Index>(2 * Eigen::Index{nev}, n));
  }
  truncate(solution.pairs, lambda_max);
  return solution;
}

}  // namespace hm::modal
