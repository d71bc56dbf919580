#pragma once
// What every assembly over the cells of a structure mesh shares: the node-major sparsity pattern
// of its matrices, a colouring of the cells for a parallel scatter without atomics, and the
// checks of the mesh itself. DOFs are interleaved node-major: node i, component c → dim·i + c.
#include <string_view>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "mesh/types.hpp"

namespace hm::fem {

/// Compressed-column pattern of a node-major matrix: column dim·j + c holds the rows dim·i + r
/// of every node i sharing a cell with node j, in order.
class BlockPattern {
 public:
  BlockPattern(const mesh::StructureMesh& mesh);

  std::size_t nonzeros() const { return inner_.size(); }
  int dim() const { return dim_; }

  /// Index into the value array of entry (dim·i + r, dim·j + c).
  std::size_t position(mesh::Index i, int r, mesh::Index j, int c) const {
    return block_position(neighbour_rank(i, j), r, j, c);
  }
  /// The rank of node i among the neighbours of node j (one search for a whole dim × dim block).
  std::size_t neighbour_rank(mesh::Index i, mesh::Index j) const;
  /// Index of entry (dim·i + r, dim·j + c) for i of neighbour_rank(i, j) = `rank`.
  std::size_t block_position(std::size_t rank, int r, mesh::Index j, int c) const {
    return static_cast<std::size_t>(outer_[static_cast<std::size_t>(dim_ * j + c)]) + dim_ * rank +
           static_cast<std::size_t>(r);
  }

  /// The matrix with `values` (nonzeros() of them, in pattern order) as entries.
  Eigen::SparseMatrix<double> matrix(const std::vector<double>& values) const;

 private:
  std::vector<std::vector<mesh::Index>> adjacency_;
  int dim_;
  std::vector<int> outer_;
  std::vector<int> inner_;
};

/// Greedy colouring of the cells such that no two cells of a colour share a node: cells of a
/// colour are scattered in parallel without atomics, colours one after the other, so every
/// matrix entry is summed in the same order whatever the thread count (bitwise reproducible).
std::vector<std::vector<mesh::Index>> colour_cells(const mesh::StructureMesh& mesh);

/// Adds one element matrix into the values of the global pattern (no other thread may touch
/// the nodes of this cell meanwhile).
void scatter(const BlockPattern& pattern, const mesh::StructureMesh& mesh, mesh::Index cell,
             const Eigen::MatrixXd& local, std::vector<double>& values);

/// Adds one element vector into a global node-major vector (same rule as scatter).
void scatter(const mesh::StructureMesh& mesh, mesh::Index cell, const Eigen::VectorXd& local,
             Eigen::VectorXd& global);

/// The element vector of one cell gathered from a global node-major vector.
Eigen::VectorXd gather(const mesh::StructureMesh& mesh, mesh::Index cell,
                       const Eigen::VectorXd& global);

/// Node coordinates of one cell (nodes × dim) [m].
Eigen::MatrixXd cell_coordinates(const mesh::StructureMesh& mesh, mesh::Index cell);

/// InputError naming `context` for a dimension other than 2 or 3, a wrong cell width, no cells,
/// or a node index out of range.
void validate_mesh(const mesh::StructureMesh& mesh, std::string_view context);

}  // namespace hm::fem
