#pragma once
// Linear polynomial part of the RBF interpolant, restricted to the directions the source points
// actually span. Source points on a plane in 3-D (a flat plate) or on a line in 2-D make the full
// basis {1, x, y, z} rank-deficient; the principal directions of the centred source coordinates
// (SVD) with a singular value below `relative_tolerance` × the largest are dropped. The kept
// directions are scaled by their singular value so that the basis columns are O(1).
#include <Eigen/Core>

#include "rbf/point_cloud.hpp"

namespace hm::rbf {

class LinearBasis {
 public:
  LinearBasis() = default;
  explicit LinearBasis(const Points& source, double relative_tolerance = 1e-6);

  /// Number of basis functions: 1 + number of kept directions.
  Eigen::Index size() const { return 1 + directions_.cols(); }
  /// Number of dropped (degenerate) directions.
  Eigen::Index dropped() const { return dropped_; }
  /// Basis evaluated at the points (n × size()).
  Eigen::MatrixXd evaluate(const Points& x) const;

 private:
  Eigen::RowVectorXd mean_;
  Eigen::MatrixXd directions_;  // d × kept, columns scaled by 1/singular value
  Eigen::Index dropped_ = 0;
};

}  // namespace hm::rbf
