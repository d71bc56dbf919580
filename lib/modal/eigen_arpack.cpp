// ARPACK-ng reverse communication for the generalised symmetric problem in shift-invert mode.
// Prototypes of the ISO-C binding are declared here rather than through <arpack.h>, whose
// C99 `_Complex` declarations ISO C++ rejects under -Wpedantic.
#include <algorithm>
#include <chrono>
#include <numeric>
#include <vector>

#include "core/errors.hpp"
#include "modal/eigen_backends.hpp"

extern "C" {
void dsaupd_c(int* ido, const char* bmat, int n, const char* which, int nev, double tol,
              double* resid, int ncv, double* v, int ldv, int* iparam, int* ipntr, double* workd,
              double* workl, int lworkl, int* info);
void dseupd_c(int rvec, const char* howmny, const int* select, double* d, double* z, int ldz,
              double sigma, const char* bmat, int n, const char* which, int nev, double tol,
              double* resid, int ncv, double* v, int ldv, int* iparam, int* ipntr, double* workd,
              double* workl, int lworkl, int* info);
}

namespace hm::modal {
namespace {

/// ARPACK's work arrays for one run.
struct ArpackState {
  int n, nev, ncv;
  std::vector<double> resid, v, workd, workl;
  int iparam[11] = {};
  int ipntr[14] = {};
  int info = 1;  // 1: use the starting vector in resid

  ArpackState(int n_, int nev_, int ncv_, const Eigen::VectorXd& start)
      : n(n_),
        nev(nev_),
        ncv(ncv_),
        resid(start.data(), start.data() + n_),
        v(static_cast<std::size_t>(n_) * ncv_),
        workd(3 * static_cast<std::size_t>(n_)),
        workl(static_cast<std::size_t>(ncv_) * (ncv_ + 8)) {}

  int lworkl() const { return static_cast<int>(workl.size()); }
  /// workd slot pointed to by the 1-based ipntr[k].
  double* slot(int k) { return &workd[static_cast<std::size_t>(ipntr[k] - 1)]; }
};

/// Runs dsaupd until it stops asking for operator applications; returns the OP count.
int iterate(const ShiftInvertOperator& op, ArpackState& s, double tol, int max_restarts) {
  s.iparam[0] = 1;  // exact shifts
  s.iparam[2] = max_restarts;
  s.iparam[6] = 3;  // shift-invert mode
  std::vector<double> mx(static_cast<std::size_t>(s.n));
  int ido = 0, op_count = 0;
  while (true) {
    dsaupd_c(&ido, "G", s.n, "LM", s.nev, tol, s.resid.data(), s.ncv, s.v.data(), s.n, s.iparam,
             s.ipntr, s.workd.data(), s.workl.data(), s.lworkl(), &s.info);
    if (ido == -1) {  // y = OP x = (K − σM)⁻¹ M x
      op.apply_mass(s.slot(0), mx.data());
      op.apply_shifted_inverse(mx.data(), s.slot(1));
      ++op_count;
    } else if (ido == 1) {  // y = (K − σM)⁻¹ (M x), with M x already in ipntr[2]
      op.apply_shifted_inverse(s.slot(2), s.slot(1));
      ++op_count;
    } else if (ido == 2) {  // y = M x
      op.apply_mass(s.slot(0), s.slot(1));
    } else {
      return op_count;
    }
  }
}

/// dseupd: the converged Ritz pairs of the original problem, λ ascending. False on an error.
bool extract(const ShiftInvertOperator& op, ArpackState& s, double tol, EigenPairs& out) {
  const int nconv = s.iparam[4];
  std::vector<int> select(static_cast<std::size_t>(s.ncv), 1);
  std::vector<double> d(static_cast<std::size_t>(s.nev));
  Eigen::MatrixXd z(s.n, s.nev);
  int info = 0;
  dseupd_c(1, "A", select.data(), d.data(), z.data(), s.n, op.shift(), "G", s.n, "LM", s.nev, tol,
           s.resid.data(), s.ncv, s.v.data(), s.n, s.iparam, s.ipntr, s.workd.data(),
           s.workl.data(), s.lworkl(), &info);
  if (info != 0) {
    out.status = EigenStatus::solver_error;
    out.message = fmt::format("ARPACK dseupd returned info = {}", info);
    return false;
  }
  std::vector<int> order(static_cast<std::size_t>(nconv));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return d[a] < d[b]; });
  out.values.resize(nconv);
  out.vectors.resize(s.n, nconv);
  for (int k = 0; k < nconv; ++k) {
    out.values(k) = d[static_cast<std::size_t>(order[k])];
    out.vectors.col(k) = z.col(order[k]);
  }
  out.converged = nconv;
  return true;
}

}  // namespace

EigenPairs arpack_shift_invert(const ShiftInvertOperator& op, int nev,
                               const LanczosOptions& options) {
  const int n = static_cast<int>(op.size());
  HM_ASSERT(nev >= 1 && nev < n, "ARPACK needs 1 ≤ nev < n; nev = {}, n = {}", nev, n);
  const auto start = std::chrono::steady_clock::now();
  ArpackState s(n, nev, subspace_size(options, nev, n),
                lanczos_start_vector(n, options.start_seed));
  EigenPairs out;
  out.requested = nev;
  out.op_applications = iterate(op, s, options.tolerance, options.max_restarts);
  out.iterations = s.iparam[2];
  if (s.info < 0 || (s.info != 0 && s.info != 1)) {
    out.status = EigenStatus::solver_error;
    out.message = fmt::format("ARPACK dsaupd returned info = {}", s.info);
  } else if (s.iparam[4] > 0) {
    if (extract(op, s, options.tolerance, out))
      out.status = out.converged >= nev ? EigenStatus::converged : EigenStatus::not_converged;
  } else {
    out.status = EigenStatus::not_converged;
  }
  if (out.status == EigenStatus::not_converged)
    out.message = fmt::format("ARPACK: {} of {} eigenpairs converged after {} restarts",
                              out.converged, nev, out.iterations);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace hm::modal
