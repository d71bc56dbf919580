// Spectra's shift-invert generalised Lanczos on our operator (not Spectra's SymShiftInvert,
// which factorises with SparseLU and loses accuracy on stiff problems; DEPENDENCIES §3.3).
#include <chrono>

#include <Spectra/SymGEigsShiftSolver.h>

#include "core/errors.hpp"
#include "modal/eigen_backends.hpp"

namespace hm::modal {
namespace {

/// (K − σM)⁻¹ as Spectra's OpType; counts its applications.
class SpectraShiftedInverse {
 public:
  using Scalar = double;
  explicit SpectraShiftedInverse(const ShiftInvertOperator& op) : op_(op) {}
  Eigen::Index rows() const { return op_.size(); }
  Eigen::Index cols() const { return op_.size(); }
  void set_shift([[maybe_unused]] double sigma) {
    HM_ASSERT(sigma == op_.shift(), "Spectra shift {} differs from the operator's {}", sigma,
              op_.shift());
  }
  void perform_op(const double* x, double* y) const {
    op_.apply_shifted_inverse(x, y);
    ++applications_;
  }
  int applications() const { return applications_; }

 private:
  const ShiftInvertOperator& op_;
  mutable int applications_ = 0;
};

/// M as Spectra's BOpType.
class SpectraMass {
 public:
  using Scalar = double;
  explicit SpectraMass(const ShiftInvertOperator& op) : op_(op) {}
  Eigen::Index rows() const { return op_.size(); }
  Eigen::Index cols() const { return op_.size(); }
  void perform_op(const double* x, double* y) const { op_.apply_mass(x, y); }

 private:
  const ShiftInvertOperator& op_;
};

}  // namespace

EigenPairs spectra_shift_invert(const ShiftInvertOperator& op, int nev,
                                const LanczosOptions& options) {
  const Eigen::Index n = op.size();
  HM_ASSERT(nev >= 1 && nev < n, "Spectra needs 1 ≤ nev < n; nev = {}, n = {}", nev, n);
  const auto start = std::chrono::steady_clock::now();
  SpectraShiftedInverse inverse(op);
  SpectraMass mass(op);
  Spectra::SymGEigsShiftSolver<SpectraShiftedInverse, SpectraMass, Spectra::GEigsMode::ShiftInvert>
      solver(inverse, mass, nev, subspace_size(options, nev, n), op.shift());
  const Eigen::VectorXd start_vector = lanczos_start_vector(n, options.start_seed);
  solver.init(start_vector.data());
  EigenPairs out;
  out.requested = nev;
  bool failed = false;
  try {
    out.converged =
        static_cast<int>(solver.compute(Spectra::SortRule::LargestMagn, options.max_restarts,
                                        options.tolerance, Spectra::SortRule::SmallestAlge));
  } catch (const std::exception& e) {  // Spectra throws on internal breakdowns
    failed = true;
    out.status = EigenStatus::solver_error;
    out.message = fmt::format("Spectra: {}", e.what());
  }
  out.iterations = static_cast<int>(solver.num_iterations());
  out.op_applications = inverse.applications();
  if (!failed) {
    out.values = solver.eigenvalues();
    out.vectors = solver.eigenvectors();
    out.converged = static_cast<int>(out.values.size());
    out.status = solver.info() == Spectra::CompInfo::Successful && out.converged >= nev
                     ? EigenStatus::converged
                     : EigenStatus::not_converged;
    if (out.status == EigenStatus::not_converged)
      out.message = fmt::format("Spectra: {} of {} eigenpairs converged after {} restarts",
                                out.converged, nev, out.iterations);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hm::modal
