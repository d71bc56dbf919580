#include "fem/assembly.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Geometry>

#include "core/errors.hpp"
#include "fem/elements.hpp"
#include "fem/pattern.hpp"

namespace hm::fem {
using mesh::Index;

SystemMatrices assemble(const mesh::StructureMesh& mesh, const ElasticModel& model,
                        std::string_view context) {
  validate(model, mesh.dim, context);
  validate_mesh(mesh, context);
  const BlockPattern pattern(mesh);
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
