#include "fem/static_solve.hpp"

#include <Eigen/SparseCholesky>

#include "core/errors.hpp"

namespace hm::fem {

Eigen::VectorXd solve_static(const SystemMatrices& system, const DofMap& dofs,
                             const Eigen::VectorXd& force) {
  HM_ASSERT(force.size() == system.dof_count(), "load has {} entries for {} DOFs", force.size(),
            system.dof_count());
  const SparseMatrix k = dofs.reduce(system.stiffness);
  Eigen::SimplicialLDLT<SparseMatrix> solver(k);
  if (solver.info() != Eigen::Success || (solver.vectorD().array() <= 0.0).any())
    numerical_error(
        "static solve: the stiffness on the {} free DOFs is singular or indefinite; "
        "the clamped nodes must prevent every rigid-body motion",
        dofs.free_count());
  const Eigen::VectorXd u = solver.solve(dofs.reduce(Eigen::MatrixXd(force)));
  return dofs.expand(u);
}

Eigen::VectorXd nodal_force(const mesh::StructureMesh& mesh, std::string_view group,
                            const Eigen::VectorXd& total_force) {
  const auto found = mesh.node_groups.find(std::string(group));
  if (found == mesh.node_groups.end() || found->second.empty())
    input_error("load: node group '{}' does not exist in the mesh or is empty", group);
  HM_ASSERT(total_force.size() == mesh.dim, "force has {} components in {}-D", total_force.size(),
            mesh.dim);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(mesh.dim * mesh.node_count());
  const double share = 1.0 / static_cast<double>(found->second.size());
  for (mesh::Index node : found->second)
    f.segment(mesh.dim * node, mesh.dim) += share * total_force;
  return f;
}

}  // namespace hm::fem
