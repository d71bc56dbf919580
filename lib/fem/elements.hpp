#pragma once
// Quadratic Lagrange elements of the structure: tri6 (2-D) and tet10 (3-D), gmsh node order
// (see mesh/types.hpp). Element matrices of linear elasticity with consistent mass.
// DOFs of an element are node-major: local node a, component c → dim·a + c.
#include <Eigen/Core>

namespace hm::fem {

/// Shape functions N (nodes) and their reference gradients dN/dξ (nodes × dim) at one point.
struct ShapeValues {
  Eigen::VectorXd n;
  Eigen::MatrixXd dn;
};

/// tri6 at reference point (ξ, η); xi.z() is ignored.
ShapeValues tri6_shape(const Eigen::Vector3d& xi);
/// tet10 at reference point (ξ, η, ζ).
ShapeValues tet10_shape(const Eigen::Vector3d& xi);

struct ElementMatrices {
  Eigen::MatrixXd stiffness;  ///< [N/m], (dim·nodes)²
  Eigen::MatrixXd mass;       ///< [kg], (dim·nodes)²
  double min_jacobian = 0.0;  ///< smallest det J over the quadrature points; ≤ 0: inverted cell
};

/// Stiffness (degree-2 rule, exact for straight-sided elements) and consistent mass (degree-4
/// rule, exact: N_a N_b is quartic) of one tri6 (coords 6×2) or tet10 (coords 10×3) cell.
/// `elasticity` is the Voigt matrix from elasticity_matrix(); `thickness` scales 2-D matrices
/// (pass 1 in 3-D).
ElementMatrices element_matrices(const Eigen::MatrixXd& coords, const Eigen::MatrixXd& elasticity,
                                 double density, double thickness);

}  // namespace hm::fem
