// ARPACK, Spectra and the dense oracle on the same small model; factorisations; frequency
// requests; non-convergence reported as a status.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "mesh/structured.hpp"
#include "modal/eigen_solve.hpp"
#include "modal/modes.hpp"
#include "test_eigen_checks.hpp"

namespace hm::modal {
namespace {

using testing::expect_mode_invariants;

/// The elastic gate (2-D plane strain, clamped at its base), coarse: 728 free DOFs.
struct GateModel {
  mesh::StructureMesh mesh = mesh::structured_rectangle(0.079, 0.005, 20, 2);
  fem::ElasticModel model{{12e6, 0.4, 1100.0}, fem::PlaneAssumption::plane_strain, 1.0};
  fem::SystemMatrices system = fem::assemble(mesh, model, "gate");
  fem::DofMap dofs = fem::DofMap::clamp_groups(mesh, std::vector<std::string>{"xmin"}, "gate");
  SparseMatrix k = dofs.reduce(system.stiffness);
  SparseMatrix m = dofs.reduce(system.mass);

  ModeSet modes(const ModeRequest& request, const EigenOptions& options) const {
    return build_mode_set(solve_eigenproblem(k, m, request, options), system, dofs, mesh,
                          Eigen::Vector3d::Zero());
  }
};

const GateModel& gate() {
  static const GateModel model;
  return model;
}

TEST(EigenBackends, ArpackSpectraAndDenseAgree) {
  const ModeRequest request{10, {}, "test"};
  std::vector<ModeSet> sets;
  for (EigenBackend backend : {EigenBackend::arpack, EigenBackend::spectra, EigenBackend::dense}) {
    EigenOptions options;
    options.backend = backend;
    sets.push_back(gate().modes(request, options));
    SCOPED_TRACE(to_string(backend));
    expect_mode_invariants(sets.back());
    EXPECT_EQ(sets.back().count(), 10);
  }
  const Eigen::VectorXd& dense = sets[2].eigenvalues;
  const double arpack_error =
      ((sets[0].eigenvalues - dense).array() / dense.array()).abs().maxCoeff();
  const double spectra_error =
      ((sets[1].eigenvalues - dense).array() / dense.array()).abs().maxCoeff();
  std::printf(
      "max relative eigenvalue difference to dense: ARPACK %.2e, Spectra %.2e "
      "(ARPACK %d OP applications, Spectra %d)\n",
      arpack_error, spectra_error, sets[0].solver.op_applications, sets[1].solver.op_applications);
  EXPECT_LT(arpack_error, 1e-8);
  EXPECT_LT(spectra_error, 1e-8);
  // Same modes, up to the documented sign convention (the spectrum here is simple).
  for (int i = 0; i < 10; ++i) {
    EXPECT_LT((sets[0].shapes.col(i) - sets[2].shapes.col(i)).norm(),
              1e-6 * sets[2].shapes.col(i).norm())
        << "mode " << i;
  }
}

TEST(EigenBackends, FactorisationsAgree) {
  const ModeRequest request{6, {}, "test"};
  EigenOptions ldlt, cholmod;
  ldlt.factorisation = Factorisation::simplicial_ldlt;
  cholmod.factorisation = Factorisation::cholmod_supernodal_llt;
  const ModeSet a = gate().modes(request, ldlt), b = gate().modes(request, cholmod);
  EXPECT_EQ(a.solver.factorisation, "simplicial_ldlt");
  EXPECT_EQ(b.solver.factorisation, "cholmod_supernodal_llt");
  expect_mode_invariants(a);
  expect_mode_invariants(b);
  EXPECT_LT(((a.eigenvalues - b.eigenvalues).array() / a.eigenvalues.array()).abs().maxCoeff(),
            1e-10);
}

TEST(EigenBackends, InteriorShiftWithLdlt) {
  // σ between the 4th and 5th eigenvalue: K − σM is indefinite; LDLᵀ still factorises it and
  // shift-invert returns the eigenvalues nearest σ.
  EigenOptions dense_options;
  dense_options.backend = EigenBackend::dense;
  const ModeSet reference = gate().modes({8, {}, "test"}, dense_options);
  EigenOptions options;
  options.shift = 0.5 * (reference.eigenvalues(3) + reference.eigenvalues(4));
  const EigenSolution s = solve_eigenproblem(gate().k, gate().m, {2, {}, "test"}, options);
  ASSERT_EQ(s.pairs.status, EigenStatus::converged);
  EXPECT_EQ(s.factorisation, Factorisation::simplicial_ldlt);
  EXPECT_NEAR(s.pairs.values(0), reference.eigenvalues(3), 1e-9 * reference.eigenvalues(3));
  EXPECT_NEAR(s.pairs.values(1), reference.eigenvalues(4), 1e-9 * reference.eigenvalues(4));
}

TEST(EigenBackends, FrequencyRequestGrowsUntilPastTheLimit) {
  EigenOptions dense_options;
  dense_options.backend = EigenBackend::dense;
  const ModeSet reference = gate().modes({30, {}, "test"}, dense_options);
  const double f_max = 0.5 * (reference.frequency_hz(16) + reference.frequency_hz(17));
  for (EigenBackend backend : {EigenBackend::arpack, EigenBackend::spectra}) {
    EigenOptions options;
    options.backend = backend;
    options.first_block = 4;  // 4 → 8 → 16 → 32 pairs
    const EigenSolution s = solve_eigenproblem(gate().k, gate().m, {0, f_max, "test"}, options);
    ASSERT_EQ(s.pairs.status, EigenStatus::converged) << s.pairs.message;
    EXPECT_EQ(s.solves, 4);
    ASSERT_EQ(s.pairs.converged, 17);
    EXPECT_LT(((s.pairs.values - reference.eigenvalues.head(17)).array() /
               reference.eigenvalues.head(17).array())
                  .abs()
                  .maxCoeff(),
              1e-8);
  }
}

TEST(EigenBackends, NonConvergenceIsAStatusWithTheConvergedCount) {
  LanczosOptions starved;
  starved.max_restarts = 1;
  starved.subspace = 12;
  const SparseShiftInvert op(gate().k, gate().m, default_shift(gate().k, gate().m));
  for (bool arpack : {true, false}) {
    const EigenPairs p =
        arpack ? arpack_shift_invert(op, 10, starved) : spectra_shift_invert(op, 10, starved);
    SCOPED_TRACE(arpack ? "arpack" : "spectra");
    EXPECT_EQ(p.status, EigenStatus::not_converged);
    EXPECT_LT(p.converged, 10);
    EXPECT_EQ(p.requested, 10);
    EXPECT_EQ(p.values.size(), p.converged);
    EXPECT_NE(p.message.find("of 10 eigenpairs converged"), std::string::npos) << p.message;
  }
}

TEST(EigenBackends, SolverInfoIsRecorded) {
  const ModeSet s = gate().modes({5, {}, "test"}, {});
  EXPECT_EQ(s.solver.backend, "arpack");
  EXPECT_EQ(s.solver.requested, 5);
  EXPECT_EQ(s.solver.converged, 5);
  EXPECT_LT(s.solver.shift, 0.0);
  EXPECT_GT(s.solver.op_applications, 5);
  EXPECT_GE(s.solver.iterations, 1);
  EXPECT_GE(s.solver.factorisation_seconds, 0.0);
  EXPECT_GT(s.solver.lanczos_seconds, 0.0);
}

TEST(Damping, UniformPerModeAndRayleigh) {
  const GateModel& g = gate();
  const EigenSolution solution = solve_eigenproblem(g.k, g.m, {3, {}, "test"}, {});
  Damping rayleigh;
  rayleigh.kind = Damping::Kind::rayleigh;
  rayleigh.alpha_per_s = 0.5;
  rayleigh.beta_s = 1e-4;
  const ModeSet r = build_mode_set(solution, g.system, g.dofs, g.mesh, {}, rayleigh);
  for (int i = 0; i < 3; ++i) {
    const double w = r.omega(i);
    EXPECT_NEAR(r.damping_ratio(i), 0.5 / (2 * w) + 1e-4 * w / 2, 1e-14);
    EXPECT_NEAR(r.damping_coefficient(i), 2 * r.damping_ratio(i) * w, 1e-12);
  }
  Damping per_mode;
  per_mode.kind = Damping::Kind::per_mode;
  per_mode.ratios = {0.01, 0.02, 0.03};
  const ModeSet p = build_mode_set(solution, g.system, g.dofs, g.mesh, {}, per_mode);
  EXPECT_DOUBLE_EQ(p.damping_ratio(2), 0.03);
  per_mode.ratios = {0.01};
  per_mode.context = "scene.toml: bodies.gate.damping";
  try {
    build_mode_set(solution, g.system, g.dofs, g.mesh, {}, per_mode);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bodies.gate.damping: 1 damping ratios given for 3 modes"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hm::modal
