#include "linsolve/linear_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

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

CsrMatrix amg_matrix(const CsrMatrix& a, double drop, int first_row) {
  HM_ASSERT(drop >= 0.0 && drop < 1.0, "amg_matrix: drop {} outside [0, 1)", drop);
  HM_ASSERT(a.isCompressed() && first_row >= 0 && first_row + a.rows() <= a.cols(),
            "amg_matrix: rows {}.. {} of a compressed matrix with {} columns", first_row,
            first_row + a.rows(), a.cols());
  if (drop == 0.0) return a;
  // Written row by row straight into the result's compressed storage (a's columns are sorted
  // in each row; at most one zero diagonal is added a row): the setup of every PPE pays for
  // this, so no triplets, no sort and no copy.
  CsrMatrix p(a.rows(), a.cols());
  p.resizeNonZeros(static_cast<Eigen::Index>(a.nonZeros() + a.rows()));
  int* starts = p.outerIndexPtr();
  int* columns = p.innerIndexPtr();
  double* values = p.valuePtr();
  int size = 0;
  starts[0] = 0;
  for (int r = 0; r < a.rows(); ++r) {
    const int d = first_row + r;  // the diagonal's column
    double largest = 0.0, lumped = 0.0;
    for (CsrMatrix::InnerIterator it(a, r); it; ++it)
      if (it.col() != d) largest = std::max(largest, std::abs(it.value()));
    int diagonal = -1;  // where the diagonal is
    const auto append = [&](int column, double value) {
      columns[size] = column;
      values[size++] = value;
    };
    for (CsrMatrix::InnerIterator it(a, r); it; ++it) {
      const bool small = it.col() != d && std::abs(it.value()) < drop * largest;
      if (small) {
        lumped += it.value();  // onto the diagonal: the row sum stays
        continue;
      }
      if (diagonal < 0 && it.col() >= d) {
        diagonal = size;
        if (it.col() > d) append(d, 0.0);  // a row without a stored diagonal: a zero one
      }
      append(static_cast<int>(it.col()), it.value());
    }
    if (diagonal < 0) {
      diagonal = size;
      append(d, 0.0);
    }
    values[diagonal] += lumped;
    starts[r + 1] = size;
  }
  p.resizeNonZeros(size);
  return p;
}

namespace {

template <typename T>
bool same_array(const T* a, const T* b, Eigen::Index n) {
  return std::equal(a, a + n, b);
}

}  // namespace

bool same_matrix(const CsrMatrix& a, const CsrMatrix& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() && a.nonZeros() == b.nonZeros() &&
         same_array(a.outerIndexPtr(), b.outerIndexPtr(), a.rows() + 1) &&
         same_array(a.innerIndexPtr(), b.innerIndexPtr(), a.nonZeros()) &&
         same_array(a.valuePtr(), b.valuePtr(), a.nonZeros());
}

double relative_residual(const CsrMatrix& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  const double norm_b = b.norm();
  if (norm_b == 0.0) return x.allFinite() ? (a * x).norm() : std::nan("");
  return (b - a * x).norm() / norm_b;
}

}  // namespace hm::linsolve
