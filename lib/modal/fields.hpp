#pragma once
// Physical fields from modal coordinates: u = Σ_i Φ_i y_i (LDD-SPEC §2.2 item 4: the paper's
// eq. (12) is misprinted), and likewise for velocity and acceleration.
// Φ is n_dofs × n_modes (mass-normalised: units 1/√kg); y in m·√kg gives u in m.
#include <Eigen/Core>

namespace hm::modal {

/// u = Φ·q. Throws InputError when Φ has a different number of modes (columns) than q.
Eigen::VectorXd modal_superposition(const Eigen::MatrixXd& phi, const Eigen::VectorXd& q);

struct PhysicalFields {
  Eigen::VectorXd displacement;  ///< m
  Eigen::VectorXd velocity;      ///< m/s
  Eigen::VectorXd acceleration;  ///< m/s²
};

/// Displacement, velocity and acceleration vectors from modal y, v, a.
PhysicalFields reconstruct_fields(const Eigen::MatrixXd& phi, const Eigen::VectorXd& y,
                                  const Eigen::VectorXd& v, const Eigen::VectorXd& a);

}  // namespace hm::modal
