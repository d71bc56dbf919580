#include "modal/modes.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "core/errors.hpp"

namespace hm::modal {
namespace {

constexpr double kRigidStrainEnergy = 1e-8;  // ‖Kφ‖ below this·‖K‖_∞‖φ‖: a rigid-body mode
constexpr double kSignTie = 1e-8;

double infinity_norm(const fem::SparseMatrix& a) {
  Eigen::VectorXd row_sums = Eigen::VectorXd::Zero(a.rows());
  for (Eigen::Index c = 0; c < a.outerSize(); ++c)
    for (fem::SparseMatrix::InnerIterator it(a, c); it; ++it)
      row_sums(it.row()) += std::abs(it.value());
  return row_sums.maxCoeff();
}

void mass_normalise(const fem::SparseMatrix& m, Eigen::MatrixXd& shapes) {
  for (Eigen::Index i = 0; i < shapes.cols(); ++i) {
    const double modal_mass = shapes.col(i).dot(m * shapes.col(i));
    shapes.col(i) /= std::sqrt(modal_mass);
  }
}

/// Largest-magnitude component positive; near-ties go to the lowest index.
void fix_signs(Eigen::MatrixXd& shapes) {
  for (Eigen::Index i = 0; i < shapes.cols(); ++i) {
    const double largest = shapes.col(i).cwiseAbs().maxCoeff();
    Eigen::Index first = 0;
    while (std::abs(shapes(first, i)) < (1.0 - kSignTie) * largest) ++first;
    if (shapes(first, i) < 0.0) shapes.col(i) *= -1.0;
  }
}

Eigen::VectorXd residuals(const fem::SystemMatrices& system, const fem::DofMap& dofs,
                          const Eigen::VectorXd& lambda, const Eigen::MatrixXd& shapes) {
  const double k_norm = infinity_norm(system.stiffness);
  Eigen::VectorXd out(shapes.cols());
  for (Eigen::Index i = 0; i < shapes.cols(); ++i) {
    Eigen::VectorXd kphi = system.stiffness * shapes.col(i);
    Eigen::VectorXd r = kphi - lambda(i) * (system.mass * shapes.col(i));
    for (Eigen::Index dof = 0; dof < r.size(); ++dof)
      if (dofs.is_clamped(dof)) r(dof) = kphi(dof) = 0.0;  // reactions, not residuals
    const double scale = k_norm * shapes.col(i).norm();
    const double elastic = kphi.norm();
    out(i) = r.norm() / (elastic > kRigidStrainEnergy * scale ? elastic : scale);
  }
  return out;
}

/// max_j |(ΦᵀMΦ − I)_ij| for every mode i.
Eigen::VectorXd orthogonality_errors(const fem::SparseMatrix& m, const Eigen::MatrixXd& shapes) {
  const Eigen::MatrixXd gram = shapes.transpose() * (m * shapes);
  return (gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols()))
      .cwiseAbs()
      .rowwise()
      .maxCoeff();
}

Eigen::VectorXd signed_sqrt(const Eigen::VectorXd& lambda) {
  return lambda.unaryExpr([](double l) { return std::copysign(std::sqrt(std::abs(l)), l); });
}

void apply_damping(const Damping& damping, ModeSet& modes) {
  const Eigen::Index n = modes.count();
  modes.damping_ratio = Eigen::VectorXd::Zero(n);
  switch (damping.kind) {
    case Damping::Kind::none:
      break;
    case Damping::Kind::uniform:
      if (!(damping.ratio >= 0.0))
        input_error("{}: damping ratio ζ = {}; it must be ≥ 0", damping.context, damping.ratio);
      modes.damping_ratio.setConstant(damping.ratio);
      break;
    case Damping::Kind::per_mode:
      if (static_cast<Eigen::Index>(damping.ratios.size()) != n)
        input_error("{}: {} damping ratios given for {} modes; give one per mode", damping.context,
                    damping.ratios.size(), n);
      for (Eigen::Index i = 0; i < n; ++i) {
        const double z = damping.ratios[static_cast<std::size_t>(i)];
        if (!(z >= 0.0))
          input_error("{}: damping ratio ζ[{}] = {}; it must be ≥ 0", damping.context, i, z);
        modes.damping_ratio(i) = z;
      }
      break;
    case Damping::Kind::rayleigh:
      if (!(damping.alpha_per_s >= 0.0 && damping.beta_s >= 0.0))
        input_error("{}: Rayleigh α = {} 1/s, β = {} s; both must be ≥ 0", damping.context,
                    damping.alpha_per_s, damping.beta_s);
      break;
  }
  modes.damping_coefficient = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double w = modes.omega(i);
    if (damping.kind == Damping::Kind::rayleigh) {
      const double c = damping.alpha_per_s + damping.beta_s * std::max(modes.eigenvalues(i), 0.0);
      modes.damping_coefficient(i) = c;
      modes.damping_ratio(i) =
          w > 0.0 ? c / (2.0 * w) : (c == 0.0 ? 0.0 : std::numeric_limits<double>::infinity());
    } else {
      modes.damping_coefficient(i) = 2.0 * modes.damping_ratio(i) * std::max(w, 0.0);
    }
  }
}

SolverInfo solver_info(const EigenSolution& s) {
  return {to_string(s.backend),
          to_string(s.factorisation),
          to_string(s.pairs.status),
          s.pairs.message,
          s.pairs.requested,
          s.pairs.converged,
          s.shift,
          s.pairs.iterations,
          s.pairs.op_applications,
          s.factorisation_seconds,
          s.pairs.seconds};
}

}  // namespace

ModeSet build_mode_set(const EigenSolution& solution, const fem::SystemMatrices& system,
                       const fem::DofMap& dofs, const mesh::StructureMesh& mesh,
                       const Eigen::Vector3d& reference_point, const Damping& damping) {
  ModeSet modes;
  modes.dim = mesh.dim;
  modes.solver = solver_info(solution);
  modes.reference_point = reference_point;
  modes.eigenvalues = solution.pairs.values;
  modes.omega = signed_sqrt(modes.eigenvalues);
  modes.frequency_hz = modes.omega / (2.0 * std::numbers::pi);
  modes.shapes = dofs.expand(solution.pairs.vectors);
  mass_normalise(system.mass, modes.shapes);
  fix_signs(modes.shapes);
  modes.residuals = residuals(system, dofs, modes.eigenvalues, modes.shapes);
  modes.orthogonality_errors = orthogonality_errors(system.mass, modes.shapes);
  modes.orthogonality_error = modes.count() > 0 ? modes.orthogonality_errors.maxCoeff() : 0.0;
  const Eigen::MatrixXd phi_t_m = modes.shapes.transpose() * system.mass;
  modes.translational_participation = phi_t_m * fem::rigid_translations(mesh);
  modes.rotational_participation = phi_t_m * fem::rigid_rotations(mesh, reference_point);
  modes.translational_effective_mass = modes.translational_participation.array().square();
  modes.rotational_effective_mass = modes.rotational_participation.array().square();
  apply_damping(damping, modes);
  return modes;
}

ModeSet compute_modes(const mesh::StructureMesh& mesh, const fem::ElasticModel& model,
                      std::span<const std::string> clamped_groups, const ModeRequest& request,
                      const EigenOptions& options, const Eigen::Vector3d& reference_point,
                      const Damping& damping, std::string_view context) {
  const fem::SystemMatrices system = fem::assemble(mesh, model, context);
  const fem::DofMap dofs = fem::DofMap::clamp_groups(mesh, clamped_groups, context);
  const EigenSolution solution =
      solve_eigenproblem(dofs.reduce(system.stiffness), dofs.reduce(system.mass), request, options);
  return build_mode_set(solution, system, dofs, mesh, reference_point, damping);
}

Eigen::VectorXd modal_static_response(const ModeSet& modes, const Eigen::VectorXd& force) {
  Eigen::VectorXd u = Eigen::VectorXd::Zero(force.size());
  for (int i = 0; i < modes.count(); ++i)
    if (modes.eigenvalues(i) > 0.0)
      u += modes.shapes.col(i) * (modes.shapes.col(i).dot(force) / modes.eigenvalues(i));
  return u;
}

}  // namespace hm::modal
