#pragma once
// The map between a finite-element structure's nodal fields and the fluid's wall of that
// structure (the surface fsi-map mapped the modes onto): any displacement field is carried to the
// wall's vertices consistently, u_w = H u, and the wall's vertex forces back conservatively,
// f = Hᵀ f_w (the same virtual work on both sides, rbf/interpolator.hpp).
// H selects the structure's boundary nodes (BoundarySurface::volume_node) and, when the wall is
// not that boundary itself (map.target = "file", map.max_edge), interpolates them onto the wall
// by the RBF of fsi-map with the same options, so u_w = H Φ reproduces mapped.h5's shapes.
// Fields are node-major, D per node or vertex [m, m/s, m/s², N].
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "mesh/types.hpp"
#include "rbf/interpolator.hpp"

namespace hm::coupling {

class FeWallMap {
 public:
  /// `surface_vertices`: the structure's boundary surface (n_s × D) and the volume node of each;
  /// `wall_vertices`: the wall's (n_w × D). The wall is the boundary itself when both vertex
  /// lists agree to 1e-9 of the body's size; otherwise the RBF map with `options`.
  FeWallMap(const Eigen::MatrixXd& surface_vertices, std::vector<mesh::Index> volume_node,
            Eigen::Index volume_nodes, const Eigen::MatrixXd& wall_vertices,
            const rbf::RbfOptions& options);

  int dim() const { return dim_; }
  Eigen::Index wall_vertices() const { return wall_count_; }
  bool identity() const { return !rbf_; }
  /// u_w = H u: D·n_w from D·n_nodes (the structure's full DOF vector).
  Eigen::VectorXd to_wall(const Eigen::VectorXd& nodal) const;
  /// Columns of full DOF vectors to wall fields.
  Eigen::MatrixXd to_wall(const Eigen::MatrixXd& nodal) const;
  /// f = Hᵀ f_w: the structure's nodal forces (full DOFs, zero off the boundary).
  Eigen::VectorXd to_structure(const Eigen::VectorXd& wall_force) const;

 private:
  /// The boundary's fields (n_s × D) of a full DOF vector, and back.
  Eigen::MatrixXd boundary_rows(const Eigen::VectorXd& nodal) const;

  int dim_ = 0;
  Eigen::Index nodes_ = 0, wall_count_ = 0;
  std::vector<mesh::Index> volume_node_;
  std::unique_ptr<rbf::RbfInterpolator> rbf_;  ///< empty: the wall is the boundary
};

}  // namespace hm::coupling
