#include "coupling/fe_wall_map.hpp"

#include "core/errors.hpp"

namespace hm::coupling {
namespace {

/// Whether two vertex lists are the same points in the same order (to 1e-9 of their extent).
bool same_vertices(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  if (a.rows() != b.rows() || a.cols() != b.cols() || a.rows() == 0) return false;
  const double extent = (a.colwise().maxCoeff() - a.colwise().minCoeff()).norm();
  return (a - b).cwiseAbs().maxCoeff() <= 1e-9 * std::max(extent, 1e-300);
}

}  // namespace

FeWallMap::FeWallMap(const Eigen::MatrixXd& surface_vertices, std::vector<mesh::Index> volume_node,
                     Eigen::Index volume_nodes, const Eigen::MatrixXd& wall_vertices,
                     const rbf::RbfOptions& options)
    : dim_(static_cast<int>(surface_vertices.cols())),
      nodes_(volume_nodes),
      wall_count_(wall_vertices.rows()),
      volume_node_(std::move(volume_node)) {
  if (static_cast<Eigen::Index>(volume_node_.size()) != surface_vertices.rows())
    input_error("structure surface: {} vertices but {} volume nodes", surface_vertices.rows(),
                volume_node_.size());
  if (wall_vertices.cols() != dim_)
    input_error("structure surface is {}-D, its wall {}-D", dim_, wall_vertices.cols());
  if (!same_vertices(surface_vertices, wall_vertices))
    rbf_ = std::make_unique<rbf::RbfInterpolator>(surface_vertices, wall_vertices, options);
}

Eigen::MatrixXd FeWallMap::boundary_rows(const Eigen::VectorXd& nodal) const {
  HM_ASSERT(nodal.size() == dim_ * nodes_, "field of {} entries for {} nodes", nodal.size(),
            nodes_);
  Eigen::MatrixXd rows(static_cast<Eigen::Index>(volume_node_.size()), dim_);
  for (std::size_t s = 0; s < volume_node_.size(); ++s)
    rows.row(static_cast<Eigen::Index>(s)) = nodal.segment(dim_ * volume_node_[s], dim_);
  return rows;
}

Eigen::VectorXd FeWallMap::to_wall(const Eigen::VectorXd& nodal) const {
  const Eigen::MatrixXd boundary = boundary_rows(nodal);
  const Eigen::MatrixXd wall = rbf_ ? rbf_->apply(boundary) : boundary;  // n_w × D
  Eigen::VectorXd out(dim_ * wall_count_);
  for (Eigen::Index v = 0; v < wall_count_; ++v) out.segment(dim_ * v, dim_) = wall.row(v);
  return out;
}

Eigen::MatrixXd FeWallMap::to_wall(const Eigen::MatrixXd& nodal) const {
  Eigen::MatrixXd out(dim_ * wall_count_, nodal.cols());
  for (Eigen::Index c = 0; c < nodal.cols(); ++c)
    out.col(c) = to_wall(Eigen::VectorXd(nodal.col(c)));
  return out;
}

Eigen::VectorXd FeWallMap::to_structure(const Eigen::VectorXd& wall_force) const {
  HM_ASSERT(wall_force.size() == dim_ * wall_count_, "wall force of {} entries for {} vertices",
            wall_force.size(), wall_count_);
  Eigen::MatrixXd wall(wall_count_, dim_);
  for (Eigen::Index v = 0; v < wall_count_; ++v) wall.row(v) = wall_force.segment(dim_ * v, dim_);
  const Eigen::MatrixXd boundary = rbf_ ? rbf_->apply_transpose(wall) : wall;  // n_s × D
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dim_ * nodes_);
  for (std::size_t s = 0; s < volume_node_.size(); ++s)
    out.segment(dim_ * volume_node_[s], dim_) += boundary.row(static_cast<Eigen::Index>(s));
  return out;
}

}  // namespace hm::coupling
