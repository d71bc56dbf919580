#pragma once
// Wendland's compactly supported C2 function, positive definite in R^d for d ≤ 3:
//   φ(r) = (1 − r)^4 (4r + 1) for 0 ≤ r < 1, 0 otherwise,   r = distance / support radius.
namespace hm::rbf {

inline double wendland_c2(double r) {
  if (r >= 1.0) return 0.0;
  const double s = 1.0 - r, s2 = s * s;
  return s2 * s2 * (4.0 * r + 1.0);
}

}  // namespace hm::rbf
