#include "linsolve/linear_solver.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/IterativeLinearSolvers>

#include "core/errors.hpp"
#include "linsolve/bicgstab.hpp"
#include "linsolve/petsc_solver.hpp"

namespace hm::linsolve {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

/// BiCGSTAB with Jacobi. A matrix whose diagonal is 1 everywhere (the row-scaled PPE) is used
/// as it is, so the iteration is the plain one; any other is row-scaled once at setup.
class JacobiSolver final : public LinearSolver {
 public:
  explicit JacobiSolver(const Settings& s) : settings_(s) {}
  Method method() const override { return Method::jacobi; }

  bool setup(const CsrMatrix& a) override {
    const auto start = Clock::now();
    setup_failure_.clear();
    matrix_ = &a;
    inverse_diagonal_.resize(0);
    scaled_.resize(0, 0);
    const Eigen::VectorXd d = a.diagonal();
    if ((d.array() != 1.0).any()) {
      if ((d.array() == 0.0).any() || !d.allFinite()) {
        setup_failure_ = "a zero or non-finite diagonal entry (Jacobi needs a nonzero diagonal)";
        setup_seconds_ = seconds_since(start);
        return false;
      }
      inverse_diagonal_ = d.cwiseInverse();
      scaled_ = inverse_diagonal_.asDiagonal() * a;
      matrix_ = &scaled_;
    }
    setup_seconds_ = seconds_since(start);
    return true;
  }
  bool reuse_for(const CsrMatrix& a) override { return setup(a); }  // nothing to keep

  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    HM_ASSERT(matrix_ != nullptr, "jacobi solver: solve before setup");
    const auto start = Clock::now();
    const auto r = inverse_diagonal_.size() == 0
                       ? bicgstab(*matrix_, b, x, settings_.tolerance, settings_.max_iterations)
                       : bicgstab(*matrix_, inverse_diagonal_.cwiseProduct(b), x,
                                  settings_.tolerance, settings_.max_iterations);
    SolveStats s;
    s.iterations = r.iterations;
    s.residual = r.residual;
    s.converged = r.converged && x.allFinite();
    s.seconds = seconds_since(start);
    if (!s.converged)
      s.failure =
          fmt::format("BiCGSTAB (Jacobi) did not reach {:.3g} in {} iterations (residual {:.3g})",
                      settings_.tolerance, r.iterations, r.residual);
    return s;
  }

 private:
  Settings settings_;
  const CsrMatrix* matrix_ = nullptr;
  Eigen::VectorXd inverse_diagonal_;  ///< empty when the diagonal is 1
  CsrMatrix scaled_;
};

/// Eigen's BiCGSTAB with IncompleteLUT: factorised serially at setup.
class IluSolver final : public LinearSolver {
 public:
  explicit IluSolver(const Settings& s) : settings_(s) {
    solver_.setTolerance(s.tolerance);
    solver_.setMaxIterations(s.max_iterations);
    solver_.preconditioner().setDroptol(s.ilu_drop);
    solver_.preconditioner().setFillfactor(s.ilu_fill);
  }
  Method method() const override { return Method::ilu; }

  bool setup(const CsrMatrix& a) override {
    const auto start = Clock::now();
    solver_.compute(a);
    ready_ = solver_.info() == Eigen::Success;
    setup_failure_ = ready_ ? "" : "the incomplete LU factorisation failed";
    setup_seconds_ = seconds_since(start);
    return ready_;
  }
  bool reuse_for(const CsrMatrix&) override { return false; }  // Eigen keeps A and M together

  SolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    SolveStats s;
    const auto start = Clock::now();
    if (!ready_) {
      s.failure = setup_failure_.empty() ? "ilu: solve before setup" : setup_failure_;
      return s;
    }
    const Eigen::VectorXd guess = x;
    x = solver_.solveWithGuess(b, guess);
    s.iterations = static_cast<int>(solver_.iterations());
    s.residual = solver_.error();
    s.converged = solver_.info() == Eigen::Success && x.allFinite();
    s.seconds = seconds_since(start);
    if (!s.converged)
      s.failure =
          fmt::format("BiCGSTAB (ILU) did not reach {:.3g} in {} iterations (residual {:.3g})",
                      settings_.tolerance, s.iterations, s.residual);
    return s;
  }

 private:
  Settings settings_;
  Eigen::BiCGSTAB<CsrMatrix, Eigen::IncompleteLUT<double, int>> solver_;
  bool ready_ = false;
};

}  // namespace

const char* to_string(Method method) {
  switch (method) {
    case Method::jacobi:
      return "jacobi";
    case Method::ilu:
      return "ilu";
    case Method::boomeramg:
      return "boomeramg";
    case Method::gamg:
      return "gamg";
  }
  return "?";
}

std::optional<Method> method_from_string(std::string_view name) {
  for (const Method m : {Method::jacobi, Method::ilu, Method::boomeramg, Method::gamg})
    if (name == to_string(m)) return m;
  return std::nullopt;
}

std::vector<Method> available_methods() {
  std::vector<Method> m{Method::jacobi, Method::ilu};
  if (petsc_available()) {
    m.push_back(Method::boomeramg);
    m.push_back(Method::gamg);
  }
  return m;
}

bool is_available(Method method) {
  return method == Method::jacobi || method == Method::ilu || petsc_available();
}

std::unique_ptr<LinearSolver> make_solver(Method method, const Settings& settings) {
  HM_ASSERT(is_available(method), "linear solver {} is not built in", to_string(method));
  switch (method) {
    case Method::jacobi:
      return std::make_unique<JacobiSolver>(settings);
    case Method::ilu:
      return std::make_unique<IluSolver>(settings);
    case Method::boomeramg:
    case Method::gamg:
      return make_petsc_solver(method, settings);
  }
  return nullptr;
}

double relative_residual(const CsrMatrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const double norm_b = b.norm();
  if (norm_b == 0.0) return x.allFinite() ? (a * x).norm() : std::nan("");
  return (b - a * x).norm() / norm_b;
}

}  // namespace hm::linsolve
