#pragma once
// Dirichlet conditions that clamp every component of a set of nodes, and the map between the
// full DOF numbering (dim·node + component) and the free DOFs that remain.
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mesh/types.hpp"

namespace hm::fem {

class DofMap {
 public:
  /// No clamped node: every DOF is free (a free-free structure).
  DofMap(Eigen::Index node_count, int dim);
  /// Clamps all components of `clamped_nodes` (duplicates allowed). Throws InputError for an
  /// index outside [0, node_count).
  DofMap(Eigen::Index node_count, int dim, std::span<const mesh::Index> clamped_nodes);

  /// Clamps the union of the named node groups of `mesh`. A missing name is an InputError that
  /// names `context` (e.g. the scene key) and lists the groups the mesh has.
  static DofMap clamp_groups(const mesh::StructureMesh& mesh, std::span<const std::string> groups,
                             std::string_view context);

  int dim() const { return dim_; }
  Eigen::Index full_count() const { return static_cast<Eigen::Index>(free_index_.size()); }
  Eigen::Index free_count() const { return static_cast<Eigen::Index>(free_dofs_.size()); }
  Eigen::Index clamped_count() const { return full_count() - free_count(); }
  bool is_clamped(Eigen::Index dof) const { return free_index_[static_cast<std::size_t>(dof)] < 0; }
  /// Full DOF of each free DOF, ascending.
  const std::vector<Eigen::Index>& free_dofs() const { return free_dofs_; }

  /// Rows and columns of the free DOFs of a full square matrix.
  Eigen::SparseMatrix<double> reduce(const Eigen::SparseMatrix<double>& full) const;
  /// Entries of the free DOFs of full vectors (columns of `full`).
  Eigen::MatrixXd reduce(const Eigen::MatrixXd& full) const;
  /// Full vectors with the free entries from `reduced` and zeros at clamped DOFs.
  Eigen::MatrixXd expand(const Eigen::MatrixXd& reduced) const;
  /// The free entries of one full vector, and the full vector (zeros at clamped DOFs) of free
  /// entries.
  Eigen::VectorXd free_values(const Eigen::VectorXd& full) const;
  Eigen::VectorXd full_values(const Eigen::VectorXd& free) const;

 private:
  int dim_;
  std::vector<Eigen::Index> free_index_;  // full DOF → free DOF, −1 if clamped
  std::vector<Eigen::Index> free_dofs_;
};

}  // namespace hm::fem
