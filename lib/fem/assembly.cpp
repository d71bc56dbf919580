#include "fem/assembly.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "fem/elements.hpp"

namespace hm::fem {
namespace {

using mesh::Index;

/// Sorted neighbour nodes of every node (itself included): the block sparsity pattern.
std::vector<std::vector<Index>> node_adjacency(const mesh::StructureMesh& mesh) {
  std::vector<std::vector<Index>> adjacent(static_cast<std::size_t>(mesh.node_count()));
  for (Index c = 0; c < mesh.cells.rows(); ++c)
    for (Index a = 0; a < mesh.cells.cols(); ++a) {
      auto& list = adjacent[static_cast<std::size_t>(mesh.cells(c, a))];
      for (Index b = 0; b < mesh.cells.cols(); ++b) list.push_back(mesh.cells(c, b));
    }
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t n = 0; n < adjacent.size(); ++n) {
    std::sort(adjacent[n].begin(), adjacent[n].end());
    adjacent[n].erase(std::unique(adjacent[n].begin(), adjacent[n].end()), adjacent[n].end());
  }
  return adjacent;
}

/// Compressed-column pattern of a node-major matrix: column dim·j + c holds the rows dim·i + r
/// of every neighbour i of node j, in order.
class BlockPattern {
 public:
  BlockPattern(std::vector<std::vector<Index>> adjacency, int dim)
      : adjacency_(std::move(adjacency)), dim_(dim) {
    outer_.reserve(dim * adjacency_.size() + 1);
    outer_.push_back(0);
    for (const auto& neighbours : adjacency_)
      for (int c = 0; c < dim_; ++c) {
        for (Index i : neighbours)
          for (int r = 0; r < dim_; ++r) inner_.push_back(static_cast<int>(dim_ * i + r));
        outer_.push_back(static_cast<int>(inner_.size()));
      }
  }

  std::size_t nonzeros() const { return inner_.size(); }

  /// Index into the value array of entry (dim·i + r, dim·j + c).
  std::size_t position(Index i, int r, Index j, int c) const {
    const auto& neighbours = adjacency_[static_cast<std::size_t>(j)];
    const auto p = std::lower_bound(neighbours.begin(), neighbours.end(), i) - neighbours.begin();
    return static_cast<std::size_t>(outer_[static_cast<std::size_t>(dim_ * j + c)] + dim_ * p + r);
  }

  SparseMatrix matrix(const std::vector<double>& values) const {
    const Eigen::Index n = static_cast<Eigen::Index>(outer_.size()) - 1;
    return Eigen::Map<const SparseMatrix>(n, n, static_cast<Eigen::Index>(inner_.size()),
                                          outer_.data(), inner_.data(), values.data());
  }

 private:
  std::vector<std::vector<Index>> adjacency_;
  int dim_;
  std::vector<int> outer_;
  std::vector<int> inner_;
};

void validate_mesh(const mesh::StructureMesh& mesh, std::string_view context) {
  if (mesh.dim != 2 && mesh.dim != 3)
    input_error("{}: mesh dimension {} is invalid; it must be 2 (tri6) or 3 (tet10)", context,
                mesh.dim);
  if (mesh.nodes.cols() != mesh.dim || mesh.cells.cols() != mesh.nodes_per_cell())
    input_error(
        "{}: a {}-D mesh needs {} coordinates per node and {} nodes per cell; got {} and {}",
        context, mesh.dim, mesh.dim, mesh.nodes_per_cell(), mesh.nodes.cols(), mesh.cells.cols());
  if (mesh.cells.rows() == 0) input_error("{}: the mesh has no cells", context);
  if (mesh.cells.size() > 0 &&
      (mesh.cells.minCoeff() < 0 || mesh.cells.maxCoeff() >= mesh.node_count()))
    input_error("{}: a cell refers to node {}; node indices must lie in [0, {})", context,
                mesh.cells.minCoeff() < 0 ? mesh.cells.minCoeff() : mesh.cells.maxCoeff(),
                mesh.node_count());
}

Eigen::MatrixXd cell_coordinates(const mesh::StructureMesh& mesh, Index cell) {
  Eigen::MatrixXd coords(mesh.cells.cols(), mesh.dim);
  for (Index a = 0; a < mesh.cells.cols(); ++a) coords.row(a) = mesh.nodes.row(mesh.cells(cell, a));
  return coords;
}

/// Greedy colouring of the cells such that no two cells of a colour share a node: cells of a
/// colour are scattered in parallel without atomics, colours one after the other, so every
/// matrix entry is summed in the same order whatever the thread count (bitwise reproducible).
std::vector<std::vector<Index>> colour_cells(const mesh::StructureMesh& mesh) {
  std::vector<std::vector<int>> node_colours(static_cast<std::size_t>(mesh.node_count()));
  std::vector<std::vector<Index>> colours;
  std::vector<char> taken;
  for (Index c = 0; c < mesh.cells.rows(); ++c) {
    taken.assign(colours.size() + 1, 0);
    for (Index a = 0; a < mesh.cells.cols(); ++a)
      for (int used : node_colours[static_cast<std::size_t>(mesh.cells(c, a))]) taken[used] = 1;
    const auto colour =
        static_cast<std::size_t>(std::find(taken.begin(), taken.end(), 0) - taken.begin());
    if (colour == colours.size()) colours.emplace_back();
    colours[colour].push_back(c);
    for (Index a = 0; a < mesh.cells.cols(); ++a)
      node_colours[static_cast<std::size_t>(mesh.cells(c, a))].push_back(static_cast<int>(colour));
  }
  return colours;
}

/// Adds one element matrix into the values of the global pattern (no other thread may touch
/// the nodes of this cell meanwhile).
void scatter(const BlockPattern& pattern, const mesh::StructureMesh& mesh, Index cell,
             const Eigen::MatrixXd& local, std::vector<double>& values) {
  const int dim = mesh.dim;
  for (Index b = 0; b < mesh.cells.cols(); ++b)
    for (int c = 0; c < dim; ++c)
      for (Index a = 0; a < mesh.cells.cols(); ++a)
        for (int r = 0; r < dim; ++r) {
          const double v = local(dim * a + r, dim * b + c);
          if (v == 0.0) continue;
          values[pattern.position(mesh.cells(cell, a), r, mesh.cells(cell, b), c)] += v;
        }
}

}  // namespace

SystemMatrices assemble(const mesh::StructureMesh& mesh, const ElasticModel& model,
                        std::string_view context) {
  validate(model, mesh.dim, context);
  validate_mesh(mesh, context);
  const BlockPattern pattern(node_adjacency(mesh), mesh.dim);
  std::vector<double> k(pattern.nonzeros(), 0.0), m(pattern.nonzeros(), 0.0);
  const Eigen::MatrixXd d = elasticity_matrix(model, mesh.dim);
  const double thickness = mesh.dim == 2 ? model.thickness_m : 1.0;
  std::atomic<Index> inverted_cell{-1};
  for (const std::vector<Index>& cells : colour_cells(mesh)) {
    const auto count = static_cast<std::int64_t>(cells.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::int64_t i = 0; i < count; ++i) {
      const Index cell = cells[static_cast<std::size_t>(i)];
      const ElementMatrices e = element_matrices(cell_coordinates(mesh, cell), d,
                                                 model.material.density_kg_m3, thickness);
      if (!(e.min_jacobian > 0.0)) inverted_cell = cell;
      scatter(pattern, mesh, cell, e.stiffness, k);
      scatter(pattern, mesh, cell, e.mass, m);
    }
  }
  if (inverted_cell >= 0)
    input_error(
        "{}: cell {} is inverted or degenerate (Jacobian determinant ≤ 0); the mesh must "
        "have positively oriented, non-degenerate cells",
        context, inverted_cell.load());
  return {mesh.dim, pattern.matrix(k), pattern.matrix(m)};
}

Eigen::MatrixXd rigid_translations(const mesh::StructureMesh& mesh) {
  const int dim = mesh.dim;
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(dim * mesh.node_count(), dim);
  for (Index i = 0; i < mesh.node_count(); ++i)
    for (int d = 0; d < dim; ++d) t(dim * i + d, d) = 1.0;
  return t;
}

Eigen::MatrixXd rigid_rotations(const mesh::StructureMesh& mesh, const Eigen::Vector3d& reference) {
  const int dim = mesh.dim;
  const int axes = dim == 3 ? 3 : 1;
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(dim * mesh.node_count(), axes);
  for (Index i = 0; i < mesh.node_count(); ++i) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    x.head(dim) = mesh.nodes.row(i).transpose();
    const Eigen::Vector3d arm = x - reference;
    for (int k = 0; k < axes; ++k) {
      const int axis = dim == 3 ? k : 2;
      const Eigen::Vector3d u = Eigen::Vector3d::Unit(axis).cross(arm);
      r.block(dim * i, k, dim, 1) = u.head(dim);
    }
  }
  return r;
}

}  // namespace hm::fem
