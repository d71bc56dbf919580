#pragma once
// Rigid prescribed motion of a wall body in 2-D or 3-D (LDD-SPEC §4.1): translation X(t) and
// rotation R(t) by the angle θ(t) about a FIXED axis e through the pivot c. A material point x0
// (position at θ = 0, X = 0) moves to
//   x(t) = c + X(t) + R(t)(x0 − c),
//   v(t) = Ẋ + Ω × r,                      r = R(t)(x0 − c),  Ω = θ̇ e,
//   a(t) = Ẍ + α × r + Ω × (Ω × r),        α = θ̈ e  (Euler and centripetal terms),
// exactly, from the exact derivatives of the laws (laws.hpp). SI units: m, s, rad.
// In 2-D the axis is z and vertex arrays have two columns.
#include <filesystem>
#include <vector>

#include <Eigen/Core>

#include "motion/laws.hpp"
#include "motion/time_table.hpp"

namespace hm::motion {

/// n × dim vertex coordinates, one vertex a row (same layout as hm::mesh::Coordinates).
using Vertices = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The body's rigid state at one time (3-D vectors; z = 0 in 2-D).
struct RigidState {
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();         ///< c, m (material, at X = 0)
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();   ///< X, m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      ///< Ẋ, m/s
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  ///< Ẍ, m/s²
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< R
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();         ///< Ω, rad/s
  Eigen::Vector3d alpha = Eigen::Vector3d::Zero();         ///< α, rad/s²
};

/// Positions, velocities and accelerations of a vertex array, each n × dim.
struct VertexKinematics {
  Vertices x, v, a;
};

class RigidMotion {
 public:
  /// dim 2 or 3; `axis` (3-D only, normalised here) is the rotation axis through `pivot`. In
  /// 2-D the axis is z and must not be given otherwise. InputError on a zero/non-finite axis.
  explicit RigidMotion(int dim, const Eigen::Vector3d& pivot = Eigen::Vector3d::Zero(),
                       const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ());

  /// Adds the translation direction · law(t) (direction is not normalised: law in units such
  /// that direction · value is in m). Several translations add up.
  void add_translation(const Eigen::Vector3d& direction, ScalarLaw law);
  /// The rotation angle θ(t) [rad] about the axis (replaces a previous one).
  void set_rotation(ScalarLaw angle);

  int dim() const { return dim_; }
  RigidState state(double t) const;
  /// x, v, a of the vertices x0 (n × dim, material positions) at time t.
  VertexKinematics kinematics(double t, const Vertices& x0) const;

 private:
  int dim_;
  Eigen::Vector3d pivot_, axis_;
  std::vector<std::pair<Eigen::Vector3d, ScalarLaw>> translations_;
  ScalarLaw angle_;
};

/// x, v, a of the vertices x0 (n × dim) for a given rigid state.
VertexKinematics kinematics(const RigidState& state, const Vertices& x0);

/// Sway A·sin(2πt/T) along `direction` (normalised here); amplitude m, period s, optional
/// C² start-up ramp over ramp_time s (laws.hpp).
RigidMotion sway_motion(int dim, const Eigen::Vector3d& direction, double amplitude, double period,
                        double ramp_time = 0.0);

/// Roll θ0·sin(2πft) about `axis` through `pivot` (2-D: about z); theta0 rad, frequency Hz,
/// optional C² start-up ramp over ramp_time s.
RigidMotion roll_motion(int dim, const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis,
                        double theta0, double frequency, double ramp_time = 0.0);

/// Motion from a CSV time table (time_table.hpp): `x [m]`, `y [m]`, `z [m]` translate along the
/// global axes, `theta [rad|deg]` rotates about `axis` through `pivot`. A `z [m]` column in 2-D
/// is an InputError.
RigidMotion table_motion(const TimeTable& table, int dim, const Eigen::Vector3d& pivot,
                         const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ());

}  // namespace hm::motion
