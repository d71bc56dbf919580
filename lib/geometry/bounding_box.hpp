#pragma once
// Axis-aligned bounding boxes of point sets [m], and the extent report that makes a millimetre /
// metre mix-up visible in the log before anything is meshed or solved.
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "mesh/types.hpp"

namespace hm::geometry {

/// Axis-aligned box [m]. 2-D data has z = 0 in both corners.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(0.0);
  Eigen::Vector3d max = Eigen::Vector3d::Constant(0.0);

  Eigen::Vector3d extent() const { return max - min; }
  Eigen::Vector3d centre() const { return 0.5 * (min + max); }
  double diagonal() const { return extent().norm(); }
  /// True when p lies in the box grown by `tolerance` [m] on every side.
  bool contains(const Eigen::Vector3d& p, double tolerance) const;
};

/// Bounding box of the rows of an n × 2 or n × 3 coordinate matrix (empty input: a zero box).
BoundingBox bounding_box(const mesh::Coordinates& points);

/// "x [0, 0.005] y [0, 0.079] z [0, 0] m (extent 0.005 × 0.079 × 0 m)".
std::string describe(const BoundingBox& box);

/// Logs the extent of `what` at info level, and a warning when the largest extent is outside
/// [1e-3 m, 1e3 m]: a model drawn in millimetres and read as metres is 1000× too large.
/// Returns whether it warned.
bool report_extent(const BoundingBox& box, std::string_view what);

}  // namespace hm::geometry
