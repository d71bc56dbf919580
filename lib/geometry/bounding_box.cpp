#include "geometry/bounding_box.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace hm::geometry {

bool BoundingBox::contains(const Eigen::Vector3d& p, double tolerance) const {
  return (p.array() >= min.array() - tolerance).all() &&
         (p.array() <= max.array() + tolerance).all();
}

BoundingBox bounding_box(const mesh::Coordinates& points) {
  BoundingBox box;
  if (points.rows() == 0) return box;
  const auto dim = points.cols();
  box.min.head(dim) = points.colwise().minCoeff().transpose();
  box.max.head(dim) = points.colwise().maxCoeff().transpose();
  return box;
}

std::string describe(const BoundingBox& box) {
  const Eigen::Vector3d e = box.extent();
  return fmt::format(
      "x [{:.6g}, {:.6g}] y [{:.6g}, {:.6g}] z [{:.6g}, {:.6g}] m (extent {:.6g} × {:.6g} × {:.6g} "
      "m)",
      box.min.x(), box.max.x(), box.min.y(), box.max.y(), box.min.z(), box.max.z(), e.x(), e.y(),
      e.z());
}

bool report_extent(const BoundingBox& box, std::string_view what) {
  const double largest = box.extent().maxCoeff();
  spdlog::info("{}: {}", what, describe(box));
  const bool suspicious = largest > 1e3 || largest < 1e-3;
  if (suspicious)
    spdlog::warn(
        "{}: largest extent {:.6g} m is outside [1e-3, 1e3] m; coordinates are read as "
        "metres unless the scene declares the file's length_unit — was it drawn in millimetres?",
        what, largest);
  return suspicious;
}

}  // namespace hm::geometry
