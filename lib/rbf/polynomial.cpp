#include "rbf/polynomial.hpp"

#include <cmath>

#include <Eigen/SVD>

namespace hm::rbf {

LinearBasis::LinearBasis(const Points& source, double relative_tolerance) {
  mean_ = source.colwise().mean();
  const Eigen::MatrixXd centred = source.rowwise() - mean_;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  const Eigen::VectorXd& sigma = svd.singularValues();  // descending
  const double largest = sigma.size() > 0 ? sigma[0] : 0.0;
  Eigen::Index kept = 0;
  while (kept < sigma.size() && largest > 0 && sigma[kept] > relative_tolerance * largest) ++kept;
  directions_.resize(source.cols(), kept);
  // Scale so that the basis column (x − mean)·v_k / (σ_k/√n) has unit RMS over the sources.
  const double root_n = std::sqrt(static_cast<double>(std::max<Eigen::Index>(source.rows(), 1)));
  for (Eigen::Index k = 0; k < kept; ++k)
    directions_.col(k) = svd.matrixV().col(k) * (root_n / sigma[k]);
  dropped_ = source.cols() - kept;
}

Eigen::MatrixXd LinearBasis::evaluate(const Points& x) const {
  Eigen::MatrixXd P(x.rows(), size());
  P.col(0).setOnes();
  if (directions_.cols() > 0) P.rightCols(directions_.cols()) = (x.rowwise() - mean_) * directions_;
  return P;
}

}  // namespace hm::rbf
