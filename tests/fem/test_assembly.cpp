// Global K and M: symmetry, total mass, rigid-body null space, the uniaxial patch test, and the
// static tip deflection of a cantilever against Timoshenko beam theory.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <omp.h>

#include "core/errors.hpp"
#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/static_solve.hpp"
#include "mesh/structured.hpp"

namespace hm::fem {
namespace {

const ElasticModel kSteel{{2.1e11, 0.3, 7850.0}, PlaneAssumption::plane_stress, 0.02};

double symmetric_error(const SparseMatrix& a) {
  return (a - SparseMatrix(a.transpose())).norm() / a.norm();
}

TEST(Assembly, SymmetricWithTotalMassAndRigidNullSpace) {
  const std::vector<mesh::StructureMesh> meshes{mesh::structured_rectangle(1.0, 0.3, 5, 2),
                                                mesh::structured_box(1.0, 0.3, 0.2, 4, 2, 2)};
  for (const mesh::StructureMesh& m : meshes) {
    const SystemMatrices s = assemble(m, kSteel, "test");
    EXPECT_EQ(s.dof_count(), m.dim * m.node_count());
    EXPECT_LT(symmetric_error(s.stiffness), 1e-14);
    EXPECT_LT(symmetric_error(s.mass), 1e-14);
    const double volume = m.dim == 2 ? 0.3 * kSteel.thickness_m : 0.3 * 0.2;
    const Eigen::MatrixXd t = rigid_translations(m);
    const Eigen::MatrixXd mt = t.transpose() * (s.mass * t);
    EXPECT_LT((mt - 7850.0 * volume * Eigen::MatrixXd::Identity(m.dim, m.dim)).norm(),
              1e-12 * 7850.0 * volume);
    Eigen::MatrixXd rigid(s.dof_count(), m.dim == 2 ? 3 : 6);
    rigid << t, rigid_rotations(m, Eigen::Vector3d(0.4, 0.1, 0.05));
    const double k_scale = s.stiffness.norm() * rigid.norm();
    EXPECT_LT((s.stiffness * rigid).norm(), 1e-13 * k_scale) << m.dim << "-D";
  }
}

TEST(Assembly, BitwiseIndependentOfThreadCount) {
  const mesh::StructureMesh m = mesh::structured_box(1.0, 0.3, 0.2, 4, 2, 2);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const SystemMatrices serial = assemble(m, kSteel, "test");
  omp_set_num_threads(std::max(threads, 2));
  const SystemMatrices parallel = assemble(m, kSteel, "test");
  omp_set_num_threads(threads);
  EXPECT_EQ(SparseMatrix(serial.stiffness - parallel.stiffness).cwiseAbs().sum(), 0.0);
  EXPECT_EQ(SparseMatrix(serial.mass - parallel.mass).cwiseAbs().sum(), 0.0);
}

TEST(Assembly, UniaxialStressPatchTest) {
  const mesh::StructureMesh m = mesh::structured_box(1.0, 0.5, 0.25, 3, 2, 2);
  const SystemMatrices s = assemble(m, kSteel, "test");
  const double strain = 1e-4, nu = kSteel.material.poisson_ratio;
  Eigen::VectorXd u(s.dof_count());
  for (mesh::Index i = 0; i < m.node_count(); ++i)
    u.segment<3>(3 * i) << strain * m.nodes(i, 0), -nu * strain * m.nodes(i, 1),
        -nu * strain * m.nodes(i, 2);
  const Eigen::VectorXd f = s.stiffness * u;
  const double force = kSteel.material.youngs_modulus_pa * strain * 0.5 * 0.25;
  // Interior nodes are in equilibrium; the xmax face carries the whole axial force.
  std::vector<bool> on_boundary(static_cast<std::size_t>(m.node_count()), false);
  for (const auto& [name, nodes] : m.node_groups)
    for (mesh::Index n : nodes) on_boundary[static_cast<std::size_t>(n)] = true;
  for (mesh::Index i = 0; i < m.node_count(); ++i)
    if (!on_boundary[static_cast<std::size_t>(i)]) {
      EXPECT_LT(f.segment<3>(3 * i).norm(), 1e-9 * force) << "node " << i;
    }
  double axial = 0.0;
  for (mesh::Index n : m.node_groups.at("xmax")) axial += f(3 * n);
  EXPECT_NEAR(axial, force, 1e-10 * force);
}

TEST(Assembly, InvertedCellIsAnInputError) {
  mesh::StructureMesh m = mesh::structured_rectangle(1.0, 1.0, 1, 1);
  std::swap(m.cells(1, 1), m.cells(1, 2));  // reverse the second triangle
  std::swap(m.cells(1, 3), m.cells(1, 5));
  try {
    assemble(m, kSteel, "mesh.h5: /structure");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("mesh.h5: /structure: cell 1 is inverted"),
              std::string::npos)
        << e.what();
  }
}

// Plane-stress cantilever, L/h = 20, tip shear load P: Timoshenko beam deflection
// δ = PL³/(3EI) + PL/(κGA), κ = 5/6. The clamped end of the 2-D solid (no rotation of the
// section, no Poisson contraction) differs from the beam model by O((h/L)²) ≈ 0.25 %.
TEST(StaticSolve, CantileverTipDeflectionMatchesTimoshenko) {
  const double length = 1.0, height = 0.05, load = 100.0;
  const mesh::StructureMesh m = mesh::structured_rectangle(length, height, 40, 4);
  const SystemMatrices s = assemble(m, kSteel, "test");
  const std::vector<std::string> clamped{"xmin"};
  const DofMap dofs = DofMap::clamp_groups(m, clamped, "test");
  const Eigen::VectorXd u =
      solve_static(s, dofs, nodal_force(m, "xmax", Eigen::Vector2d(0.0, -load)));
  double tip = 0.0;
  for (mesh::Index n : m.node_groups.at("xmax")) tip += u(2 * n + 1);
  tip /= static_cast<double>(m.node_groups.at("xmax").size());
  const double e = kSteel.material.youngs_modulus_pa, nu = kSteel.material.poisson_ratio;
  const double area = height * kSteel.thickness_m;
  const double inertia = kSteel.thickness_m * std::pow(height, 3) / 12.0;
  const double expected = load * std::pow(length, 3) / (3 * e * inertia) +
                          load * length / (5.0 / 6.0 * e / (2 * (1 + nu)) * area);
  std::printf("cantilever tip deflection: FE %.6e m, Timoshenko %.6e m, relative difference %.2e\n",
              -tip, expected, -tip / expected - 1.0);
  EXPECT_NEAR(-tip, expected, 5e-3 * expected);
}

TEST(StaticSolve, UnconstrainedStructureIsANumericalError) {
  const mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.1, 4, 1);
  const SystemMatrices s = assemble(m, kSteel, "test");
  EXPECT_THROW(solve_static(s, DofMap(m.node_count(), 2), Eigen::VectorXd::Ones(s.dof_count())),
               NumericalError);
}

}  // namespace
}  // namespace hm::fem
