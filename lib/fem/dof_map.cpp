#include "fem/dof_map.hpp"

#include <vector>

#include <fmt/ranges.h>

#include "core/errors.hpp"

namespace hm::fem {

DofMap::DofMap(Eigen::Index node_count, int dim) : DofMap(node_count, dim, {}) {}

DofMap::DofMap(Eigen::Index node_count, int dim, std::span<const mesh::Index> clamped_nodes)
    : dim_(dim), free_index_(static_cast<std::size_t>(dim * node_count), 0) {
  for (mesh::Index node : clamped_nodes) {
    if (node < 0 || node >= node_count)
      input_error("clamped node {} does not exist; node indices lie in [0, {})", node, node_count);
    for (int c = 0; c < dim; ++c) free_index_[static_cast<std::size_t>(dim * node + c)] = -1;
  }
  for (std::size_t dof = 0; dof < free_index_.size(); ++dof) {
    if (free_index_[dof] < 0) continue;
    free_index_[dof] = static_cast<Eigen::Index>(free_dofs_.size());
    free_dofs_.push_back(static_cast<Eigen::Index>(dof));
  }
}

DofMap DofMap::clamp_groups(const mesh::StructureMesh& mesh, std::span<const std::string> groups,
                            std::string_view context) {
  std::vector<mesh::Index> nodes;
  for (const std::string& name : groups) {
    const auto found = mesh.node_groups.find(name);
    if (found == mesh.node_groups.end()) {
      std::vector<std::string> available;
      for (const auto& [group, members] : mesh.node_groups) available.push_back(group);
      input_error("{}: node group '{}' does not exist in the mesh; available groups: [{}]", context,
                  name, fmt::join(available, ", "));
    }
    nodes.insert(nodes.end(), found->second.begin(), found->second.end());
  }
  return DofMap(mesh.node_count(), mesh.dim, nodes);
}

Eigen::SparseMatrix<double> DofMap::reduce(const Eigen::SparseMatrix<double>& full) const {
  // Columns and rows keep their order (free_index_ is increasing), so the compressed arrays of
  // the result are filled directly, column by column (no triplets, no copy).
  if (!full.isCompressed()) return reduce(Eigen::SparseMatrix<double>(full));
  Eigen::SparseMatrix<double> out(free_count(), free_count());
  out.resizeNonZeros(full.nonZeros());
  int* outer = out.outerIndexPtr();
  int* inner = out.innerIndexPtr();
  double* values = out.valuePtr();
  int count = 0;
  Eigen::Index column = 0;
  outer[0] = 0;
  for (Eigen::Index col = 0; col < full.outerSize(); ++col) {
    if (free_index_[static_cast<std::size_t>(col)] < 0) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(full, col); it; ++it) {
      const Eigen::Index r = free_index_[static_cast<std::size_t>(it.row())];
      if (r < 0) continue;
      inner[count] = static_cast<int>(r);
      values[count] = it.value();
      ++count;
    }
    outer[++column] = count;
  }
  out.resizeNonZeros(count);
  return out;
}

Eigen::VectorXd DofMap::free_values(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(free_count());
  for (Eigen::Index i = 0; i < free_count(); ++i)
    out[i] = full[free_dofs_[static_cast<std::size_t>(i)]];
  return out;
}

Eigen::VectorXd DofMap::full_values(const Eigen::VectorXd& free) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(full_count());
  for (Eigen::Index i = 0; i < free_count(); ++i)
    out[free_dofs_[static_cast<std::size_t>(i)]] = free[i];
  return out;
}

Eigen::MatrixXd DofMap::reduce(const Eigen::MatrixXd& full) const {
  Eigen::MatrixXd reduced(free_count(), full.cols());
  for (Eigen::Index i = 0; i < free_count(); ++i)
    reduced.row(i) = full.row(free_dofs_[static_cast<std::size_t>(i)]);
  return reduced;
}

Eigen::MatrixXd DofMap::expand(const Eigen::MatrixXd& reduced) const {
  Eigen::MatrixXd full = Eigen::MatrixXd::Zero(full_count(), reduced.cols());
  for (Eigen::Index i = 0; i < free_count(); ++i)
    full.row(free_dofs_[static_cast<std::size_t>(i)]) = reduced.row(i);
  return full;
}

}  // namespace hm::fem
