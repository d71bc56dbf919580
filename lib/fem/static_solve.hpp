#pragma once
// Linear static response K u = f on the free DOFs.
#include <Eigen/Core>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"

namespace hm::fem {

/// Full displacement vector [m] (zeros at clamped DOFs) under the full load vector `force` [N]
/// (its entries at clamped DOFs are reactions and ignored). Throws NumericalError if the
/// reduced stiffness is singular (e.g. the clamps leave a rigid-body motion free).
Eigen::VectorXd solve_static(const SystemMatrices& system, const DofMap& dofs,
                             const Eigen::VectorXd& force);

/// Load vector of a total force [N] spread equally over the nodes of a node group.
Eigen::VectorXd nodal_force(const mesh::StructureMesh& mesh, std::string_view group,
                            const Eigen::VectorXd& total_force);

}  // namespace hm::fem
