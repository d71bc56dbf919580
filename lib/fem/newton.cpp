#include "fem/newton.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <Eigen/UmfPackSupport>

#include "core/errors.hpp"
#include "core/log.hpp"

#include <fmt/format.h>

namespace hm::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// Unsymmetric Newton matrices of at least this many rows go to UMFPACK, smaller ones to
/// Eigen's SparseLU. Measured (bench_structure, BM_TangentLu, release, one thread, 2-core
/// machine beside other runs): on the energy-conserving tangent of the 3-D baffle (26.5 k DOFs)
/// UMFPACK factorises in 1.0–1.45 s against SparseLU's 3.1–3.5 s (2.4–3.1×); on the 2-D gate
/// (640 DOFs) SparseLU takes 0.8–1.4 ms against UMFPACK's 1.5–5.6 ms, and keeps the 2-D runs'
/// results as they were.
constexpr Eigen::Index kUmfpackRows = 5000;

struct TangentSolver::Impl {
  enum class Active { none, llt, ldlt, lu, umfpack };
  Active active = Active::none;
  Eigen::CholmodSupernodalLLT<SparseMatrix, Eigen::Lower> llt;
  Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt;
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu;
  Eigen::UmfPackLU<SparseMatrix> umfpack;
  SparseMatrix umfpack_matrix;  ///< the matrix umfpack was factorised from (see factorize_umfpack)
  bool llt_analysed = false, ldlt_analysed = false, lu_analysed = false, umfpack_analysed = false;

  Impl() {
    llt.cholmod().print = 0;  // an indefinite matrix is expected now and then: LDLᵀ takes it
  }
  bool factorize_llt(const SparseMatrix& a) {
    if (!llt_analysed) llt.analyzePattern(a);
    llt_analysed = true;
    llt.factorize(a);
    return llt.info() == Eigen::Success;
  }
  bool factorize_ldlt(const SparseMatrix& a) {
    if (!ldlt_analysed) ldlt.analyzePattern(a);
    ldlt_analysed = true;
    ldlt.factorize(a);
    return ldlt.info() == Eigen::Success;
  }
  bool factorize_lu(const SparseMatrix& a) {
    if (!lu_analysed) lu.analyzePattern(a);
    lu_analysed = true;
    lu.factorize(a);
    return lu.info() == Eigen::Success;
  }
  bool factorize_umfpack(const SparseMatrix& a) {
    // Eigen's UmfPackLU keeps a reference to the matrix, and umfpack_solve reads it again (its
    // iterative refinement): the solves need their own copy, which lives as long as the factor.
    umfpack_matrix = a;
    if (!umfpack_analysed) umfpack.analyzePattern(umfpack_matrix);
    umfpack_analysed = true;
    umfpack.factorize(umfpack_matrix);
    return umfpack.info() == Eigen::Success;
  }
};

TangentSolver::TangentSolver() : impl_(std::make_unique<Impl>()) {}
TangentSolver::~TangentSolver() = default;
TangentSolver::TangentSolver(TangentSolver&&) noexcept = default;
TangentSolver& TangentSolver::operator=(TangentSolver&&) noexcept = default;

bool TangentSolver::factorize(const SparseMatrix& matrix, bool symmetric) {
  using Active = Impl::Active;
  impl_->active = Active::none;
  if (symmetric) {
    if (impl_->factorize_llt(matrix))
      impl_->active = Active::llt;
    else if (impl_->factorize_ldlt(matrix))
      impl_->active = Active::ldlt;
  }
  if (impl_->active != Active::none) return true;
  if (matrix.rows() >= kUmfpackRows) {
    if (impl_->factorize_umfpack(matrix)) impl_->active = Active::umfpack;
  } else if (impl_->factorize_lu(matrix)) {
    impl_->active = Active::lu;
  }
  return impl_->active != Active::none;
}

Eigen::VectorXd TangentSolver::solve(const Eigen::VectorXd& rhs) const {
  using Active = Impl::Active;
  switch (impl_->active) {
    case Active::llt:
      return impl_->llt.solve(rhs);
    case Active::ldlt:
      return impl_->ldlt.solve(rhs);
    case Active::lu:
      return impl_->lu.solve(rhs);
    case Active::umfpack:
      return impl_->umfpack.solve(rhs);
    case Active::none:
      break;
  }
  HM_ASSERT(false, "TangentSolver::solve before a successful factorize");
  return {};
}

Eigen::MatrixXd TangentSolver::solve(const Eigen::MatrixXd& rhs) const {
  using Active = Impl::Active;
  switch (impl_->active) {
    case Active::llt:
      return impl_->llt.solve(rhs);
    case Active::ldlt:
      return impl_->ldlt.solve(rhs);
    case Active::lu:
      return impl_->lu.solve(rhs);
    case Active::umfpack:
      return impl_->umfpack.solve(rhs);
    case Active::none:
      break;
  }
  HM_ASSERT(false, "TangentSolver::solve before a successful factorize");
  return {};
}

namespace {

bool inverted(const NewtonSystem& s) {
  return !(s.min_det_f > 0.0);
}

}  // namespace

NewtonReport newton_solve(Eigen::VectorXd& x, const NewtonEquations& equations,
                          const NewtonOptions& options, TangentSolver& solver) {
  NewtonReport report;
  NewtonSystem system = equations(x, true);
  report.min_det_f = system.min_det_f;
  if (inverted(system)) {
    report.worst_cell = system.worst_cell;
    report.failure = fmt::format("cell {} is inverted at the start (det F = {:.3g})",
                                 system.worst_cell, system.min_det_f);
    return report;
  }
  for (int iteration = 0;; ++iteration) {
    const double norm = system.residual.norm();
    report.iterations = iteration;
    report.residual = norm / system.scale;
    if (!std::isfinite(norm)) {
      report.failure = "the residual is not finite";
      return report;
    }
    if (report.residual <= options.tolerance) {
      report.converged = true;
      return report;
    }
    if (iteration >= options.max_iterations) {
      report.worst_cell = system.worst_cell;
      report.failure = fmt::format(
          "no convergence in {} iterations (residual {:.3e} > {:.1e}; smallest det F {:.3g}, in "
          "cell {})",
          options.max_iterations, report.residual, options.tolerance, system.min_det_f,
          system.worst_cell);
      return report;
    }
    if (!solver.factorize(system.jacobian, system.symmetric)) {
      report.failure = "the Newton matrix is singular";
      return report;
    }
    const Eigen::VectorXd step = -solver.solve(system.residual);
    if (step.norm() <= options.increment_tolerance * x.norm()) {
      x += step;
      report.iterations = iteration + 1;
      report.converged = true;
      return report;
    }
    // Line search on the slope g(s) = δᵀ r(x + sδ), the derivative of the energy along δ for a
    // conservative problem (a residual-norm search would refuse the full steps of a slender
    // body, whose first iterates carry large membrane residuals and still converge). A step
    // that inverts an element is halved.
    const double slope0 = step.dot(system.residual);
    spdlog::trace("newton iteration {}: residual {:.3e}, |step| {:.3e}, |x| {:.3e}", iteration,
                  report.residual, step.norm(), x.norm());
    double fraction = 1.0;
    std::optional<Eigen::VectorXd> accepted;
    NewtonSystem trial_system;
    bool with_jacobian = false;
    for (int search = 0; search <= 8; ++search) {
      Eigen::VectorXd trial = x + fraction * step;
      NewtonSystem s = equations(trial, search == 0);
      if (inverted(s)) {
        report.worst_cell = s.worst_cell;
        fraction *= 0.5;
        continue;
      }
      accepted = std::move(trial);
      trial_system = std::move(s);
      with_jacobian = search == 0;
      const double slope = step.dot(trial_system.residual);
      // Only for a symmetric Newton matrix is the slope an energy's derivative.
      const bool descent = system.symmetric && slope0 < 0.0;
      if (!options.line_search || !descent || slope <= 0.0 ||
          std::abs(slope) <= 0.8 * std::abs(slope0) || search >= 4)
        break;
      // The slope changed sign: the secant root of g between 0 and the present fraction.
      fraction *= std::clamp(slope0 / (slope0 - slope), 0.1, 0.9);
    }
    if (!accepted) {
      report.failure = fmt::format("every step of iteration {} inverts cell {} (det F ≤ 0)",
                                   iteration + 1, report.worst_cell);
      return report;
    }
    x = std::move(*accepted);
    system = with_jacobian ? std::move(trial_system) : equations(x, true);
    report.min_det_f = system.min_det_f;
  }
}

}  // namespace hm::fem
