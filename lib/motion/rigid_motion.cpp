#include "motion/rigid_motion.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "core/errors.hpp"

namespace hm::motion {
namespace {

Eigen::Vector3d unit_vector(const Eigen::Vector3d& d, const char* what) {
  const double norm = d.norm();
  if (!(norm > 0.0) || !std::isfinite(norm))
    input_error("{} ({}, {}, {}) is invalid: expected a non-zero finite vector", what, d.x(), d.y(),
                d.z());
  return d / norm;
}

void check_planar(int dim, const Eigen::Vector3d& d, const char* what) {
  if (dim == 2 && d.z() != 0.0)
    input_error("{} ({}, {}, {}) has a z component in a 2-D case; expected z = 0", what, d.x(),
                d.y(), d.z());
}

}  // namespace

RigidMotion::RigidMotion(int dim, const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis)
    : dim_(dim), pivot_(pivot), axis_(unit_vector(axis, "rotation axis")) {
  if (dim != 2 && dim != 3) input_error("motion dimension {} is invalid: expected 2 or 3", dim);
  check_planar(dim, pivot, "rotation pivot");
  if (dim == 2 && axis_ != Eigen::Vector3d::UnitZ())
    input_error("rotation axis ({}, {}, {}) in a 2-D case: expected (0, 0, 1)", axis.x(), axis.y(),
                axis.z());
}

void RigidMotion::add_translation(const Eigen::Vector3d& direction, ScalarLaw law) {
  check_planar(dim_, direction, "translation direction");
  translations_.emplace_back(direction, std::move(law));
}

void RigidMotion::set_rotation(ScalarLaw angle) {
  angle_ = std::move(angle);
}

RigidState RigidMotion::state(double t) const {
  RigidState s;
  s.pivot = pivot_;
  for (const auto& [direction, law] : translations_) {
    const Jet f = law(t);
    s.translation += f.value * direction;
    s.velocity += f.rate * direction;
    s.acceleration += f.accel * direction;
  }
  if (angle_) {
    const Jet theta = angle_(t);
    s.rotation = Eigen::AngleAxisd(theta.value, axis_).toRotationMatrix();
    s.omega = theta.rate * axis_;
    s.alpha = theta.accel * axis_;
  }
  return s;
}

VertexKinematics RigidMotion::kinematics(double t, const Vertices& x0) const {
  HM_ASSERT(x0.cols() == dim_, "vertex array has {} columns, motion is {}-D", x0.cols(), dim_);
  return motion::kinematics(state(t), x0);
}

VertexKinematics kinematics(const RigidState& s, const Vertices& x0) {
  const Eigen::Index n = x0.rows();
  const Eigen::Index dim = x0.cols();
  HM_ASSERT(dim == 2 || dim == 3, "vertex array has {} columns", dim);
  VertexKinematics k{Vertices(n, dim), Vertices(n, dim), Vertices(n, dim)};
  const Eigen::Vector3d centre = s.pivot + s.translation;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    p.head(dim) = x0.row(i).transpose();
    const Eigen::Vector3d r = s.rotation * (p - s.pivot);
    const Eigen::Vector3d x = centre + r;
    const Eigen::Vector3d v = s.velocity + s.omega.cross(r);
    const Eigen::Vector3d a = s.acceleration + s.alpha.cross(r) + s.omega.cross(s.omega.cross(r));
    k.x.row(i) = x.head(dim).transpose();
    k.v.row(i) = v.head(dim).transpose();
    k.a.row(i) = a.head(dim).transpose();
  }
  return k;
}

RigidMotion sway_motion(int dim, const Eigen::Vector3d& direction, double amplitude, double period,
                        double ramp_time) {
  if (!(period > 0.0) || !std::isfinite(period))
    input_error("sway period {} s is invalid: expected a finite value > 0", period);
  RigidMotion motion(dim);
  motion.add_translation(unit_vector(direction, "sway direction"),
                         ramped(sine_law(amplitude, 1.0 / period), ramp_time));
  return motion;
}

RigidMotion roll_motion(int dim, const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis,
                        double theta0, double frequency, double ramp_time) {
  if (!(frequency > 0.0) || !std::isfinite(frequency))
    input_error("roll frequency {} Hz is invalid: expected a finite value > 0", frequency);
  RigidMotion motion(dim, pivot, axis);
  motion.set_rotation(ramped(sine_law(theta0, frequency), ramp_time));
  return motion;
}

RigidMotion table_motion(const TimeTable& table, int dim, const Eigen::Vector3d& pivot,
                         const Eigen::Vector3d& axis) {
  RigidMotion motion(dim, pivot, axis);
  for (std::size_t k = 0; k < table.columns.size(); ++k) {
    const auto& name = table.columns[k];
    if (name == "x [m]") motion.add_translation(Eigen::Vector3d::UnitX(), table_law(table, k));
    if (name == "y [m]") motion.add_translation(Eigen::Vector3d::UnitY(), table_law(table, k));
    if (name == "z [m]") {
      if (dim == 2)
        input_error("{}:1: column 'z [m]' in a 2-D case; expected only x [m], y [m], theta",
                    table.file);
      motion.add_translation(Eigen::Vector3d::UnitZ(), table_law(table, k));
    }
    if (name == "theta [rad]") motion.set_rotation(table_law(table, k));
    if (name == "theta [deg]") motion.set_rotation(table_law(table, k, std::numbers::pi / 180.0));
  }
  return motion;
}

}  // namespace hm::motion
