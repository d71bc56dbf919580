#pragma once
// Independent long-double references for the CFPI tests: closed-form solutions of
//   ÿ + 2ζω ẏ + ω² y = F0 + r·t   from (y0, v0)
// written per damping regime (no shared code with lib/modal/cfpi.cpp), and a long-double
// scaling-and-squaring matrix exponential of the augmented 4×4 system.
#include <array>
#include <cmath>

namespace hm::modal::test {

using ld = long double;
struct State {
  ld y, v;
};

/// Free response at time t from (y0, v0).
inline State free_response(ld omega, ld zeta, ld y0, ld v0, ld t) {
  if (zeta < 1) {
    const ld wd = omega * std::sqrt(1 - zeta * zeta);
    const ld e = std::exp(-zeta * omega * t), C = std::cos(wd * t), S = std::sin(wd * t);
    return {e * (y0 * C + (v0 + zeta * omega * y0) / wd * S),
            e * (v0 * C - (zeta * omega * v0 + omega * omega * y0) / wd * S)};
  }
  if (zeta == 1) {
    const ld e = std::exp(-omega * t), B = v0 + omega * y0;
    return {e * (y0 + B * t), e * (v0 - omega * B * t)};
  }
  const ld q = std::sqrt((zeta - 1) * (zeta + 1));
  const ld r1 = -omega / (zeta + q), r2 = -omega * (zeta + q);
  const ld c1 = (v0 - r2 * y0) / (r1 - r2), c2 = (r1 * y0 - v0) / (r1 - r2);
  const ld e1 = std::exp(r1 * t), e2 = std::exp(r2 * t);
  return {c1 * e1 + c2 * e2, r1 * c1 * e1 + r2 * c2 * e2};
}

/// Response at time t to the load F(t) = F0 + r·t from (y0, v0): particular solution
/// y_p = (F0 + r t)/ω² − 2ζr/ω³ (ẏ_p = r/ω²) plus the free response of the remainder.
inline State linear_load_response(ld omega, ld zeta, ld y0, ld v0, ld F0, ld r, ld t) {
  const ld w2 = omega * omega;
  const ld yp0 = F0 / w2 - 2 * zeta * r / (w2 * omega), vp = r / w2;
  const State h = free_response(omega, zeta, y0 - yp0, v0 - vp, t);
  return {h.y + yp0 + r * t / w2, h.v + vp};
}

using Mat4 = std::array<std::array<ld, 4>, 4>;

inline Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 c{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) c[i][j] += a[i][k] * b[k][j];
  return c;
}

/// exp(θ·M) for M = [[0,1,0,0],[-1,-2ζ,1,0],[0,0,0,1],[0,0,0,0]] (ω = 1), long double,
/// scaling and squaring with a 40-term Taylor series.
inline Mat4 augmented_expm(ld zeta, ld theta) {
  Mat4 M{};
  M[0][1] = theta;
  M[1][0] = -theta;
  M[1][1] = -2 * zeta * theta;
  M[1][2] = theta;
  M[2][3] = theta;
  const ld norm = theta * (2 + 2 * zeta);
  int s = 0;
  while (std::ldexp(norm, -s) > 0.25L) ++s;
  for (auto& row : M)
    for (auto& x : row) x = std::ldexp(x, -s);
  Mat4 E{}, term{};
  for (int i = 0; i < 4; ++i) E[i][i] = term[i][i] = 1;
  for (int k = 1; k <= 40; ++k) {
    term = multiply(term, M);
    for (auto& row : term)
      for (auto& x : row) x /= k;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) E[i][j] += term[i][j];
  }
  for (int i = 0; i < s; ++i) E = multiply(E, E);
  return E;
}

}  // namespace hm::modal::test
