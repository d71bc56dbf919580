#include "fem/pattern.hpp"

#include <algorithm>

#include "core/errors.hpp"

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

}  // namespace

BlockPattern::BlockPattern(const mesh::StructureMesh& mesh)
    : adjacency_(node_adjacency(mesh)), dim_(mesh.dim) {
  outer_.reserve(dim_ * adjacency_.size() + 1);
  outer_.push_back(0);
  for (const auto& neighbours : adjacency_)
    for (int c = 0; c < dim_; ++c) {
      for (Index i : neighbours)
        for (int r = 0; r < dim_; ++r) inner_.push_back(static_cast<int>(dim_ * i + r));
      outer_.push_back(static_cast<int>(inner_.size()));
    }
}

std::size_t BlockPattern::neighbour_rank(Index i, Index j) const {
  const auto& neighbours = adjacency_[static_cast<std::size_t>(j)];
  return static_cast<std::size_t>(std::lower_bound(neighbours.begin(), neighbours.end(), i) -
                                  neighbours.begin());
}

Eigen::SparseMatrix<double> BlockPattern::matrix(const std::vector<double>& values) const {
  // The compressed arrays copied as they are (a Map assigned to a matrix goes entry by entry).
  const Eigen::Index n = static_cast<Eigen::Index>(outer_.size()) - 1;
  Eigen::SparseMatrix<double> out(n, n);
  out.resizeNonZeros(static_cast<Eigen::Index>(inner_.size()));
  std::copy(outer_.begin(), outer_.end(), out.outerIndexPtr());
  std::copy(inner_.begin(), inner_.end(), out.innerIndexPtr());
  std::copy(values.begin(), values.end(), out.valuePtr());
  return out;
}

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

void scatter(const BlockPattern& pattern, const mesh::StructureMesh& mesh, Index cell,
             const Eigen::MatrixXd& local, std::vector<double>& values) {
  const int dim = mesh.dim;
  for (Index b = 0; b < mesh.cells.cols(); ++b) {
    const Index j = mesh.cells(cell, b);
    for (Index a = 0; a < mesh.cells.cols(); ++a) {
      const std::size_t rank = pattern.neighbour_rank(mesh.cells(cell, a), j);
      for (int c = 0; c < dim; ++c)
        for (int r = 0; r < dim; ++r) {
          const double v = local(dim * a + r, dim * b + c);
          if (v == 0.0) continue;
          values[pattern.block_position(rank, r, j, c)] += v;
        }
    }
  }
}

void scatter(const mesh::StructureMesh& mesh, Index cell, const Eigen::VectorXd& local,
             Eigen::VectorXd& global) {
  const int dim = mesh.dim;
  for (Index a = 0; a < mesh.cells.cols(); ++a)
    global.segment(dim * mesh.cells(cell, a), dim) += local.segment(dim * a, dim);
}

Eigen::VectorXd gather(const mesh::StructureMesh& mesh, Index cell, const Eigen::VectorXd& global) {
  const int dim = mesh.dim;
  Eigen::VectorXd local(dim * mesh.cells.cols());
  for (Index a = 0; a < mesh.cells.cols(); ++a)
    local.segment(dim * a, dim) = global.segment(dim * mesh.cells(cell, a), dim);
  return local;
}

Eigen::MatrixXd cell_coordinates(const mesh::StructureMesh& mesh, Index cell) {
  Eigen::MatrixXd coords(mesh.cells.cols(), mesh.dim);
  for (Index a = 0; a < mesh.cells.cols(); ++a) coords.row(a) = mesh.nodes.row(mesh.cells(cell, a));
  return coords;
}

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

}  // namespace hm::fem
