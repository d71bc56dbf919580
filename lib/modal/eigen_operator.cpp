#include "modal/eigen_operator.hpp"

#include <chrono>
#include <optional>

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>

#include "core/errors.hpp"

namespace hm::modal {

namespace {
constexpr Eigen::Index kSupernodalThreshold = 20000;
}

struct SparseShiftInvert::Factor {
  std::optional<Eigen::SimplicialLDLT<SparseMatrix>> ldlt;
  std::optional<Eigen::CholmodSupernodalLLT<SparseMatrix>> llt;
};

std::string to_string(Factorisation f) {
  switch (f) {
    case Factorisation::automatic:
      return "automatic";
    case Factorisation::simplicial_ldlt:
      return "simplicial_ldlt";
    case Factorisation::cholmod_supernodal_llt:
      return "cholmod_supernodal_llt";
  }
  return "unknown";
}

SparseShiftInvert::SparseShiftInvert(const SparseMatrix& stiffness, const SparseMatrix& mass,
                                     double shift, Factorisation factorisation)
    : mass_(mass), shift_(shift), factor_(std::make_unique<Factor>()) {
  HM_ASSERT(stiffness.rows() == mass.rows() && stiffness.cols() == mass.cols() &&
                stiffness.rows() == stiffness.cols(),
            "K is {}×{}, M is {}×{}", stiffness.rows(), stiffness.cols(), mass.rows(), mass.cols());
  const auto start = std::chrono::steady_clock::now();
  const SparseMatrix shifted = stiffness - shift * mass;
  const bool try_llt = factorisation == Factorisation::cholmod_supernodal_llt ||
                       (factorisation == Factorisation::automatic && shift < 0.0 &&
                        stiffness.rows() >= kSupernodalThreshold);
  if (try_llt) {
    factor_->llt.emplace(shifted);
    ok_ = factor_->llt->info() == Eigen::Success;
    used_ = Factorisation::cholmod_supernodal_llt;
    if (!ok_ && factorisation == Factorisation::automatic) factor_->llt.reset();
  }
  if (!factor_->llt) {
    factor_->ldlt.emplace(shifted);
    // An exactly zero pivot means σ is an eigenvalue (or K − σM is singular).
    ok_ =
        factor_->ldlt->info() == Eigen::Success && (factor_->ldlt->vectorD().array() != 0.0).all();
    used_ = Factorisation::simplicial_ldlt;
  }
  seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

SparseShiftInvert::~SparseShiftInvert() = default;

void SparseShiftInvert::apply_shifted_inverse(const double* x, double* y) const {
  const Eigen::Map<const Eigen::VectorXd> in(x, size());
  Eigen::Map<Eigen::VectorXd> out(y, size());
  if (factor_->llt)
    out = factor_->llt->solve(in);
  else
    out = factor_->ldlt->solve(in);
}

void SparseShiftInvert::apply_mass(const double* x, double* y) const {
  Eigen::Map<Eigen::VectorXd>(y, size()).noalias() =
      mass_ * Eigen::Map<const Eigen::VectorXd>(x, size());
}

}  // namespace hm::modal
