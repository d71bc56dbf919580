#pragma once
// Gauss quadrature on the reference triangle {ξ, η ≥ 0, ξ + η ≤ 1} (area 1/2) and the reference
// tetrahedron {ξ, η, ζ ≥ 0, ξ + η + ζ ≤ 1} (volume 1/6). All weights are positive.
#include <vector>

#include <Eigen/Core>

namespace hm::fem {

struct QuadratureRule {
  std::vector<Eigen::Vector3d> points;  ///< reference coordinates (ζ = 0 on the triangle)
  std::vector<double> weights;          ///< sum to the reference measure
  int degree = 0;                       ///< polynomials up to this degree are integrated exactly
};

/// Rule exact for polynomials of degree ≤ `degree` (supported: 1..4; the rule returned may be
/// of higher degree). 3 points for degree 2, 6 points (Dunavant/Strang–Fix) for degree 4.
const QuadratureRule& triangle_rule(int degree);

/// Rule exact for degree ≤ `degree` (supported: 1..5). 4 points for degree 2, 14 points
/// (Walkington, degree 5) for degrees 3..5.
const QuadratureRule& tetrahedron_rule(int degree);

}  // namespace hm::fem
