#pragma once
// A set of natural modes of a linear structure, ready for modal superposition:
//   K φ_i = λ_i M φ_i,  λ_i = ω_i² [rad²/s²],  f_i = ω_i / 2π [Hz],  Φᵀ M Φ = I.
// Conventions:
//   * sorted by λ ascending; ω_i = sign(λ_i)·√|λ_i| (a rigid-body mode may come out at λ ≈ −ε:
//     its ω and f are then tiny and negative rather than NaN);
//   * shapes are full DOF vectors (dim·node + component, zeros at clamped DOFs), n_dofs × n_modes,
//     mass-normalised: φ_iᵀ M φ_i = 1 [units of φ: kg^-½];
//   * sign: the component of largest magnitude is positive; components within a relative 1e-8
//     of the largest count as ties, and the lowest DOF index among them decides. (The basis of a
//     repeated eigenvalue, e.g. the two bending planes of a square beam, is not unique.)
//   * residual_i = ‖Kφ_i − λ_i Mφ_i‖ / ‖Kφ_i‖ for an elastic mode; for a rigid-body mode, where
//     Kφ_i is round-off (‖Kφ_i‖ ≤ 1e-8·‖K‖_∞‖φ_i‖), the backward error ‖Kφ_i − λ_i Mφ_i‖ /
//     (‖K‖_∞‖φ_i‖) instead; evaluated on the free DOFs;
//   * participation factors Γ = Φᵀ M T [kg^½] with T the rigid translations (columns x, y[, z])
//     and Φᵀ M R [kg^½·m] with R the rigid rotations about `reference_point` (about x, y, z in
//     3-D; about z in 2-D); effective modal masses Γ² [kg] and [kg·m²]. Summed over all modes
//     they give the total mass and the moments of inertia about the reference point.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "modal/eigen_solve.hpp"

namespace hm::modal {

/// Modal damping: none, one ratio for every mode, one per mode, or Rayleigh C = αM + βK with
/// ζ_i = α/(2ω_i) + β ω_i/2.
struct Damping {
  enum class Kind { none, uniform, per_mode, rayleigh };
  Kind kind = Kind::none;
  double ratio = 0.0;               ///< uniform ζ [-]
  std::vector<double> ratios;       ///< per-mode ζ [-]
  double alpha_per_s = 0.0;         ///< Rayleigh α [1/s]
  double beta_s = 0.0;              ///< Rayleigh β [s]
  std::string context = "damping";  ///< scene key for messages
};

struct SolverInfo {
  std::string backend;
  std::string factorisation;
  std::string status;  ///< to_string(EigenStatus)
  std::string message;
  int requested = 0;
  int converged = 0;
  double shift = 0.0;  ///< σ [rad²/s²]
  int iterations = 0;
  int op_applications = 0;
  double factorisation_seconds = 0.0;
  double lanczos_seconds = 0.0;
};

struct ModeSet {
  int dim = 3;
  Eigen::VectorXd eigenvalues;           ///< λ [rad²/s²]
  Eigen::VectorXd omega;                 ///< ω [rad/s]
  Eigen::VectorXd frequency_hz;          ///< f [Hz]
  Eigen::MatrixXd shapes;                ///< n_dofs × n_modes, mass-normalised
  Eigen::VectorXd residuals;             ///< relative residual per mode (see header comment)
  double orthogonality_error = 0;        ///< max |ΦᵀMΦ − I|
  Eigen::VectorXd orthogonality_errors;  ///< per mode i: max_j |(ΦᵀMΦ − I)_ij|
  Eigen::Vector3d reference_point = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::MatrixXd translational_participation;                ///< n_modes × dim [kg^½]
  Eigen::MatrixXd rotational_participation;                   ///< n_modes × (3 | 1) [kg^½·m]
  Eigen::MatrixXd translational_effective_mass;               ///< n_modes × dim [kg]
  Eigen::MatrixXd rotational_effective_mass;                  ///< n_modes × (3 | 1) [kg·m²]
  Eigen::VectorXd damping_ratio;                              ///< ζ per mode [-]
  /// Modal damping coefficient c_i = 2ζ_iω_i [1/s]; finite for rigid-body modes under Rayleigh
  /// damping (c = α + βλ), where ζ itself is undefined (reported as 0 if c = 0, else +∞).
  Eigen::VectorXd damping_coefficient;
  SolverInfo solver;

  int count() const { return static_cast<int>(eigenvalues.size()); }
};

/// Normalises, orients and checks the converged pairs of `solution` (eigenvectors on the free
/// DOFs of `dofs`) and derives the modal quantities. `system` holds the full K and M.
ModeSet build_mode_set(const EigenSolution& solution, const fem::SystemMatrices& system,
                       const fem::DofMap& dofs, const mesh::StructureMesh& mesh,
                       const Eigen::Vector3d& reference_point, const Damping& damping = {});

/// Mesh → K, M → clamps → eigenproblem → ModeSet: the whole structure side of fsi-modes.
/// `clamped_groups` names node groups of the mesh (empty: free-free). `context` prefixes
/// input-error messages (e.g. "scene.toml: structure").
ModeSet compute_modes(const mesh::StructureMesh& mesh, const fem::ElasticModel& model,
                      std::span<const std::string> clamped_groups, const ModeRequest& request,
                      const EigenOptions& options, const Eigen::Vector3d& reference_point,
                      const Damping& damping, std::string_view context);

/// Static response of the mode set to a full load vector f: Σ φ_i φ_iᵀ f / λ_i over the modes
/// with λ_i > 0 [m].
Eigen::VectorXd modal_static_response(const ModeSet& modes, const Eigen::VectorXd& force);

}  // namespace hm::modal
