#pragma once
// Small types shared by the LDD (Lagrangian differencing dynamics) numerical core, for 2-D and
// 3-D from one code base: the dimension D is a template parameter, instantiated for 2 and 3 in
// the .cpp files. Lengths in metres, velocities in m/s, pressure in Pa (gauge), density kg/m³.
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace hm::ldd {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;

/// Index of a point (a run holds fewer than 2³¹ points).
using Index = std::int32_t;

/// n × D coordinates, one point a row (the layout of mesh and motion vertex arrays and of
/// artefact matrices).
using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// The rows of an n × D matrix as points.
template <int D>
std::vector<Vec<D>> points_of(const RowMatrix& rows) {
  std::vector<Vec<D>> out(static_cast<std::size_t>(rows.rows()));
  for (Eigen::Index i = 0; i < rows.rows(); ++i)
    out[static_cast<std::size_t>(i)] = rows.row(i).transpose();
  return out;
}

/// Points as the rows of an n × D matrix.
template <int D>
RowMatrix rows_of(const std::vector<Vec<D>>& points) {
  RowMatrix out(static_cast<Eigen::Index>(points.size()), D);
  for (std::size_t i = 0; i < points.size(); ++i)
    out.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return out;
}

/// Weight of eqs. (6)–(9): Wendland C2, W(q) = (1 − q)⁴(1 + 4q) for q = r/h < 1, else 0.
/// The operators are invariant to a scaling of W, so it is not normalised.
inline double wendland_c2(double q) {
  if (q >= 1.0) return 0.0;
  const double s = 1.0 - q, s2 = s * s;
  return s2 * s2 * (1.0 + 4.0 * q);
}

/// dW/dq of wendland_c2: −20 q (1 − q)³ for q < 1, else 0.
inline double wendland_c2_derivative(double q) {
  if (q >= 1.0) return 0.0;
  const double s = 1.0 - q;
  return -20.0 * q * s * s * s;
}

/// Calls visit(c) for the 3^D cells within one cell of `centre`, the first axis fastest, until
/// visit returns true; returns whether one did.
template <int D, typename Visit>
bool any_cell_around(const std::array<std::int64_t, D>& centre, Visit&& visit) {
  std::array<std::int64_t, D> offset;
  offset.fill(-1);
  while (true) {
    std::array<std::int64_t, D> c;
    for (int a = 0; a < D; ++a) c[a] = centre[a] + offset[a];
    if (visit(c)) return true;
    int a = 0;
    while (a < D && ++offset[a] > 1) offset[a++] = -1;
    if (a == D) return false;
  }
}

}  // namespace hm::ldd
