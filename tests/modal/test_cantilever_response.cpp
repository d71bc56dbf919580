// The paper's cantilever check (its §4.1.2) on real FE modes: the 2-D elastic-gate strip
// (L = 0.079 m, h = 0.005 m, E = 12 MPa, nu = 0.4, rho = 1100 kg/m^3, plane strain), clamped at
// one end, a 1 N load suddenly applied at the free end, five modes, integrated with CFPI.
// Reference: the corrected step response of LDD-SPEC §2.2 (mode-shape factors and the
// zeta/sqrt(1 - zeta^2) sin term that the paper's eq. 19 omits):
//   u_tip(t) = sum_i phi_i(tip) [phi_i(tip) F] / w_i^2 [1 - e^{-z w_i t}(cos w_di t + z/sqrt(1-z^2)
//   sin w_di t)].
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/static_solve.hpp"
#include "mesh/structured.hpp"
#include "modal/cfpi.hpp"
#include "modal/eigen_solve.hpp"
#include "modal/modes.hpp"

namespace {

struct Cantilever {
  hm::mesh::StructureMesh mesh = hm::mesh::structured_rectangle(0.079, 0.005, 64, 4);
  hm::fem::ElasticModel model{{12e6, 0.4, 1100.0}, hm::fem::PlaneAssumption::plane_strain, 1.0};
  hm::fem::SystemMatrices system = hm::fem::assemble(mesh, model, "test");
  hm::fem::DofMap dofs =
      hm::fem::DofMap::clamp_groups(mesh, std::vector<std::string>{"xmin"}, "test");
  Eigen::VectorXd force =
      hm::fem::nodal_force(mesh, "xmax", Eigen::Vector2d(0.0, 1.0));  // 1 N along y
  hm::modal::ModeSet modes(double zeta) const {
    hm::modal::ModeRequest request{.count = 5, .max_frequency_hz = std::nullopt, .context = "test"};
    const auto solution = hm::modal::solve_eigenproblem(dofs.reduce(system.stiffness),
                                                        dofs.reduce(system.mass), request);
    hm::modal::Damping damping;
    damping.kind = zeta > 0 ? hm::modal::Damping::Kind::uniform : hm::modal::Damping::Kind::none;
    damping.ratio = zeta;
    return hm::modal::build_mode_set(solution, system, dofs, mesh, Eigen::Vector3d::Zero(),
                                     damping);
  }
  /// The y DOF of the node at the middle of the free end.
  Eigen::Index tip_dof() const {
    Eigen::Index best = 0;
    for (Eigen::Index n = 0; n < mesh.node_count(); ++n)
      if ((mesh.nodes.row(n) - Eigen::RowVector2d(0.079, 0.0025)).norm() <
          (mesh.nodes.row(best) - Eigen::RowVector2d(0.079, 0.0025)).norm())
        best = n;
    return 2 * best + 1;
  }
};

double analytic_tip(const hm::modal::ModeSet& m, const Eigen::VectorXd& force, Eigen::Index tip,
                    double t) {
  double u = 0.0;
  for (int i = 0; i < m.count(); ++i) {
    const double w = m.omega[i], z = m.damping_ratio[i], wd = w * std::sqrt(1 - z * z);
    const double modal_force = m.shapes.col(i).dot(force);
    u += m.shapes(tip, i) * modal_force / (w * w) *
         (1 -
          std::exp(-z * w * t) * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t)));
  }
  return u;
}

}  // namespace

TEST(CantileverTipLoad, CfpiMatchesCorrectedAnalyticStepResponse) {
  const Cantilever c;
  for (double zeta : {0.0, 0.02}) {
    const hm::modal::ModeSet m = c.modes(zeta);
    const Eigen::VectorXd modal_force = m.shapes.transpose() * c.force;  // constant from t = 0
    hm::modal::CfpiIntegrator cfpi(m.omega, m.damping_ratio);
    cfpi.set_state(Eigen::VectorXd::Zero(5), Eigen::VectorXd::Zero(5), modal_force);
    const double dt = 1e-4, t_end = 0.5;  // 7 periods of mode 1, omega_5 dt ~ 0.3
    const Eigen::Index tip = c.tip_dof();
    double worst = 0.0, peak = 0.0;
    for (int n = 1; n * dt <= t_end + 1e-12; ++n) {
      cfpi.step(modal_force, modal_force, dt);
      const double numeric = m.shapes.row(tip).dot(cfpi.y());
      const double exact = analytic_tip(m, c.force, tip, n * dt);
      worst = std::max(worst, std::abs(numeric - exact));
      peak = std::max(peak, std::abs(exact));
    }
    std::printf("zeta = %g: peak tip deflection %.6e m, max relative CFPI error %.3e\n", zeta, peak,
                worst / peak);
    EXPECT_LE(worst / peak, 1e-8) << "zeta = " << zeta;
    EXPECT_GT(peak, 1e-3) << "a 1 N tip load bends this soft strip by millimetres";
  }
}

TEST(CantileverTipLoad, DampedResponseSettlesOnTruncatedStaticSolution) {
  const Cantilever c;
  const hm::modal::ModeSet m = c.modes(0.2);
  const Eigen::VectorXd modal_force = m.shapes.transpose() * c.force;
  hm::modal::CfpiIntegrator cfpi(m.omega, m.damping_ratio);
  cfpi.set_state(Eigen::VectorXd::Zero(5), Eigen::VectorXd::Zero(5), modal_force);
  for (int n = 0; n < 200; ++n) cfpi.step(modal_force, modal_force, 0.01);  // 2 s = 30 periods
  const Eigen::VectorXd settled = m.shapes * cfpi.y();
  const Eigen::VectorXd truncated = hm::modal::modal_static_response(m, c.force);
  EXPECT_LE((settled - truncated).cwiseAbs().maxCoeff(), 1e-9 * truncated.cwiseAbs().maxCoeff());
  // Five modes already hold the full FE static tip deflection to better than 0.5 %.
  const Eigen::VectorXd full = hm::fem::solve_static(c.system, c.dofs, c.force);
  std::printf("tip: FE static %.6e m, 5-mode static %.6e m (%.3f %%), settled CFPI %.6e m\n",
              full[c.tip_dof()], truncated[c.tip_dof()],
              100 * (truncated[c.tip_dof()] / full[c.tip_dof()] - 1), settled[c.tip_dof()]);
  EXPECT_NEAR(truncated[c.tip_dof()], full[c.tip_dof()], 5e-3 * std::abs(full[c.tip_dof()]));
}
