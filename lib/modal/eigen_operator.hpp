#pragma once
// The generalised eigenproblem K φ = λ M φ (K symmetric positive semi-definite stiffness,
// M symmetric positive definite mass, on the free DOFs; λ = ω² [rad²/s²]) as the Lanczos
// solvers see it: operators, not storage (STYLE item 5). Shift-invert turns the eigenvalues
// nearest σ into the largest ones of OP = (K − σM)⁻¹ M, ν = 1/(λ − σ).
#include <memory>
#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace hm::modal {

using SparseMatrix = Eigen::SparseMatrix<double>;

/// What a shift-invert Lanczos solver may do with the problem.
class ShiftInvertOperator {
 public:
  virtual ~ShiftInvertOperator() = default;
  virtual Eigen::Index size() const = 0;
  /// σ [rad²/s²]
  virtual double shift() const = 0;
  /// y = (K − σM)⁻¹ x; x and y hold size() entries and do not alias.
  virtual void apply_shifted_inverse(const double* x, double* y) const = 0;
  /// y = M x
  virtual void apply_mass(const double* x, double* y) const = 0;
};

enum class Factorisation {
  automatic,               ///< CHOLMOD supernodal LLᵀ for σ < 0 and ≥ 20 000 DOFs, else LDLᵀ
  simplicial_ldlt,         ///< Eigen::SimplicialLDLT (AMD ordering); copes with indefinite shifts
  cholmod_supernodal_llt,  ///< CHOLMOD supernodal LLᵀ; needs K − σM positive definite (σ < λ₁)
};

std::string to_string(Factorisation f);

/// K − σM factorised once at construction; borrows M, which must outlive the operator.
/// Construction never throws on a failed factorisation: check ok(). With `automatic`, a failed
/// CHOLMOD LLᵀ (the shift was not below the spectrum) falls back to LDLᵀ.
class SparseShiftInvert final : public ShiftInvertOperator {
 public:
  SparseShiftInvert(const SparseMatrix& stiffness, const SparseMatrix& mass, double shift,
                    Factorisation factorisation = Factorisation::automatic);
  ~SparseShiftInvert() override;
  SparseShiftInvert(const SparseShiftInvert&) = delete;
  SparseShiftInvert& operator=(const SparseShiftInvert&) = delete;

  Eigen::Index size() const override { return mass_.rows(); }
  double shift() const override { return shift_; }
  void apply_shifted_inverse(const double* x, double* y) const override;
  void apply_mass(const double* x, double* y) const override;

  bool ok() const { return ok_; }
  /// The factorisation actually used.
  Factorisation factorisation() const { return used_; }
  double factorisation_seconds() const { return seconds_; }

 private:
  struct Factor;
  const SparseMatrix& mass_;
  double shift_;
  std::unique_ptr<Factor> factor_;
  Factorisation used_ = Factorisation::simplicial_ldlt;
  bool ok_ = false;
  double seconds_ = 0.0;
};

}  // namespace hm::modal
