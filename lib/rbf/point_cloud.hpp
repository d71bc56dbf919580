#pragma once
// Point clouds for the RBF mapping: points are the ROWS of an n × d matrix (d = 2 or 3, metres).
#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace hm::rbf {

using Points = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;  // n × d, one point a row

/// Affine map x ↦ (x − centre)/scale that takes the source bounding box to size ~1 around 0.
struct Normalisation {
  Eigen::RowVectorXd centre;
  double scale = 1.0;  ///< m per normalised unit (largest bounding-box extent)
  Points apply(const Points& x) const;
};

/// Centre and largest extent of the bounding box of the points.
Normalisation bounding_box_normalisation(const Points& x);

/// Length of the bounding-box diagonal [same units as the points].
double bounding_box_diagonal(const Points& x);

/// k-d tree (nanoflann) over a point set it owns.
class PointTree {
 public:
  explicit PointTree(Points points);
  ~PointTree();
  PointTree(const PointTree&) = delete;
  PointTree& operator=(const PointTree&) = delete;

  const Points& points() const { return points_; }
  /// Index of and distance to the nearest point.
  std::pair<Eigen::Index, double> nearest(const double* query) const;
  /// The k nearest points (index, distance), nearest first.
  std::vector<std::pair<Eigen::Index, double>> nearest_k(const double* query, int k) const;
  /// Every point within `radius` (index, distance), unsorted.
  std::vector<std::pair<Eigen::Index, double>> within(const double* query, double radius) const;

 private:
  struct Index;
  Points points_;
  std::unique_ptr<Index> index_;
};

}  // namespace hm::rbf
