#pragma once
// Global stiffness K [N/m] and consistent mass M [kg] of a structure mesh (2-D: per the
// thickness of the ElasticModel). DOFs are interleaved node-major: node i, component c →
// dim·i + c. Both matrices are symmetric, stored in full (both triangles).
#include <string_view>

#include <Eigen/SparseCore>

#include "fem/material.hpp"
#include "mesh/types.hpp"

namespace hm::fem {

using SparseMatrix = Eigen::SparseMatrix<double>;

struct SystemMatrices {
  int dim = 3;
  SparseMatrix stiffness;  ///< K, n_dofs × n_dofs
  SparseMatrix mass;       ///< M, n_dofs × n_dofs
  Eigen::Index dof_count() const { return stiffness.rows(); }
};

/// Assembles K and M. The sparsity pattern comes from the node adjacency of the cells, and the
/// cells are integrated in parallel (OpenMP, by colours of cells sharing no node) straight into
/// it; the result is bitwise independent of the thread count. Throws InputError naming
/// `context` for an invalid model, a cell with an out-of-range node index, or an inverted cell.
SystemMatrices assemble(const mesh::StructureMesh& mesh, const ElasticModel& model,
                        std::string_view context);

/// Rigid translation fields (n_dofs × dim, column d = unit displacement along axis d).
Eigen::MatrixXd rigid_translations(const mesh::StructureMesh& mesh);

/// Rigid rotation fields about `reference` [m]: n_dofs × 3 in 3-D (unit rotation about x, y,
/// z: u = e_k × (x − reference)), n_dofs × 1 in 2-D (about z). Displacement per radian [m].
Eigen::MatrixXd rigid_rotations(const mesh::StructureMesh& mesh, const Eigen::Vector3d& reference);

}  // namespace hm::fem
