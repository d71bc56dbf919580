// Operators of eqs. 6–9 and the second-order WLS Laplacian: exactness on jittered clouds and
// observed convergence orders, 2-D and 3-D.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "clouds.hpp"
#include "ldd/operators.hpp"

namespace hm::ldd {
namespace {

template <int D>
struct Cloud {
  std::vector<Vec<D>> x;
  Neighbours nb;
  Operators<D> ops;
  Vec<D> lo, hi;
};

template <int D>
Cloud<D> make_cloud(int cells, double jitter, LaplacianScheme scheme, unsigned seed = 7) {
  Cloud<D> c;
  c.lo = Vec<D>::Constant(-0.3);
  c.lo[0] = 0.2;  // off the origin, so that |r|² is not symmetric about the cloud
  c.hi = c.lo + Vec<D>::Constant(1.0);
  const double dx = 1.0 / cells;
  c.x = test::lattice<D>(c.lo, c.hi, dx, jitter, seed);
  c.nb = find_neighbours<D>(c.x, 2.5 * dx);
  OperatorOptions opt;
  opt.laplacian = scheme;
  c.ops = compute_operators<D>(c.x, c.nb, opt);
  return c;
}

template <int D>
std::vector<double> sample(const std::vector<Vec<D>>& x, auto&& f) {
  std::vector<double> v(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) v[i] = f(x[i]);
  return v;
}

template <int D>
void check_linear_and_r2_exact(int cells) {
  auto c = make_cloud<D>(cells, 0.3, LaplacianScheme::offset_vector);
  Vec<D> a;
  for (int k = 0; k < D; ++k) a[k] = 1.5 - 0.7 * k;
  const auto lin = sample<D>(c.x, [&](const Vec<D>& p) { return 2.0 + a.dot(p); });
  const auto r2 = sample<D>(c.x, [&](const Vec<D>& p) { return p.squaredNorm(); });
  const auto g = gradient<D>(c.x, c.nb, c.ops, lin);
  const auto lap = laplacian<D>(c.nb, c.ops, r2);
  const auto lap_lin = laplacian<D>(c.nb, c.ops, lin);
  std::vector<Vec<D>> u(c.x.size());
  for (std::size_t i = 0; i < c.x.size(); ++i) u[i] = Mat<D>::Identity() * 0.5 * c.x[i] + a;
  const auto div = divergence<D>(c.x, c.nb, c.ops, u);
  int degenerate = 0;
  double eg = 0, el = 0, el1 = 0, ed = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    ASSERT_FALSE(c.ops.isolated(static_cast<Index>(i)));
    if (c.ops.flags[i] & op_degenerate) {
      ++degenerate;
      continue;
    }
    eg = std::max(eg, (g[i] - a).norm());
    el = std::max(el, std::abs(lap[i] - 2.0 * D));
    el1 = std::max(el1, std::abs(lap_lin[i]));
    ed = std::max(ed, std::abs(div[i] - 0.5 * D));
  }
  EXPECT_EQ(degenerate, 0);
  EXPECT_LT(eg, 1e-10) << "gradient of a linear field";
  EXPECT_LT(ed, 1e-10) << "divergence of a linear field";
  EXPECT_LT(el, 1e-10) << "eq. 7 Laplacian of |r|²";
  EXPECT_LT(el1, 1e-10) << "eq. 7 Laplacian of a linear field";
  ::testing::Test::RecordProperty("max_gradient_error", std::to_string(eg));
  ::testing::Test::RecordProperty("max_laplacian_r2_error", std::to_string(el));
}

/// A 2-D fluid lattice above a floor at y = 0 (first layer dx/2 above it, jittered by 0.2 dx)
/// and wall nodes (normal +y, at rest) on the floor for x < wetted only: the edge of a wetted
/// floor, where the wall nodes under a point are not symmetric about it.
struct FluidOnAFloor {
  PointSet<2> points;
  Neighbours nb;
  Operators<2> ops;
  double dx = 0.02;

  explicit FluidOnAFloor(double wetted) {
    for (const auto& x : test::lattice<2>(Vec<2>(0, 0), Vec<2>(1, 0.2), dx, 0.2, 3))
      points.add_fluid(x);
    for (double x = 0.5 * dx; x < wetted; x += dx)
      points.add_wall_node(Vec<2>(x, 0), Vec<2>(0, 1), WallHost<2>{});
    nb = find_neighbours<2>(points.position, 2.5 * dx);
    ops = compute_operators<2>(points.position, nb);
  }
  bool fluid(std::size_t i) const { return points.kind[i] == PointKind::fluid; }
};

// The slip-wall velocity gradient (free slip: the wall node takes the fluid point's tangential
// velocity and the wall's normal one). A film sliding at U over a wall at rest has no
// divergence; the plain operator, which sees the nodes' zero tangential velocity, gives one of
// order U/dx at the edge of the wetted floor (the K&O surge-tip runaway). A velocity field that
// meets the wall's no-penetration condition, u = (0, −a y), is reproduced exactly at every
// fluid point, the first layer included.
TEST(LddOperators, SlipWallGradient) {
  FluidOnAFloor c(0.5);
  const double U = 2.0, a = 3.0;
  std::vector<Vec<2>> sliding(c.points.position.size(), Vec<2>(U, 0));
  std::vector<Vec<2>> squeezed(c.points.position.size());
  for (std::size_t i = 0; i < squeezed.size(); ++i)
    squeezed[i] = c.fluid(i) ? Vec<2>(0, -a * c.points.position[i].y()) : Vec<2>::Zero();
  const auto g_sliding = slip_velocity_gradient<2>(c.points, c.nb, c.ops, sliding);
  const auto g_squeezed = slip_velocity_gradient<2>(c.points, c.nb, c.ops, squeezed);
  std::vector<Vec<2>> sliding_no_slip = sliding;
  for (std::size_t i = 0; i < sliding.size(); ++i)
    if (!c.fluid(i)) sliding_no_slip[i].setZero();
  const auto div_no_slip = divergence<2>(c.points.position, c.nb, c.ops, sliding_no_slip);
  double worst_sliding = 0, worst_squeezed = 0, worst_no_slip = 0;
  Mat<2> exact;
  exact << 0, 0, 0, -a;
  for (std::size_t i = 0; i < sliding.size(); ++i) {
    if (!c.fluid(i)) continue;
    worst_sliding = std::max(worst_sliding, g_sliding[i].norm());
    worst_squeezed = std::max(worst_squeezed, (g_squeezed[i] - exact).norm());
    worst_no_slip = std::max(worst_no_slip, std::abs(div_no_slip[i]));
  }
  std::printf(
      "sliding film: |grad u| %.2e (slip), |div u| %.3g 1/s with the nodes' no-slip "
      "velocity (U/dx = %.0f 1/s); u = (0, -a y): error %.2e\n",
      worst_sliding, worst_no_slip, U / c.dx, worst_squeezed);
  EXPECT_LT(worst_sliding, 1e-10);
  EXPECT_LT(worst_squeezed, 1e-10 * a);
  EXPECT_GT(worst_no_slip, 0.1 * U / c.dx);  // what the slip rule removes
}

TEST(LddOperators, Exact2DJittered) {
  check_linear_and_r2_exact<2>(20);
}
TEST(LddOperators, Exact3DJittered) {
  check_linear_and_r2_exact<3>(8);
}

/// A general quadratic with mixed terms; its Laplacian.
template <int D>
double quadratic(const Vec<D>& p) {
  double f = 1.0 + p[0] - 2.0 * p[1] + 3.0 * p[0] * p[0] - 2.0 * p[0] * p[1] + 0.5 * p[1] * p[1];
  if constexpr (D == 3) f += -p[2] * p[2] + 4.0 * p[0] * p[2] + 1.5 * p[1] * p[2] + p[2];
  return f;
}
template <int D>
constexpr double quadratic_laplacian = D == 2 ? 7.0 : 5.0;

template <int D>
void check_wls_quadratic_exact(int cells) {
  auto c = make_cloud<D>(cells, 0.3, LaplacianScheme::wls_where_needed);
  const double dx = 1.0 / cells;
  const auto f = sample<D>(c.x, [](const Vec<D>& p) { return quadratic<D>(p); });
  const auto lap = laplacian<D>(c.nb, c.ops, f);
  int boundary = 0, boundary_wls = 0, deep = 0, deep_wls = 0;
  double err = 0.0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (test::depth_in_box<D>(c.x[i], c.lo, c.hi) > 2.5 * dx) {
      ++deep;
      deep_wls += (c.ops.flags[i] & op_wls) ? 1 : 0;
    }
    if (test::depth_in_box<D>(c.x[i], c.lo, c.hi) > 0.8 * dx) continue;  // the outer layer
    ++boundary;
    if (!(c.ops.flags[i] & op_wls)) {
      ADD_FAILURE() << "outer point " << i << " at " << c.x[i].transpose()
                    << " has no WLS row: offset ratio " << c.ops.offset_ratio[i] << ", flags "
                    << int(c.ops.flags[i]);
      continue;
    }
    ++boundary_wls;
    err = std::max(err, std::abs(lap[i] - quadratic_laplacian<D>));
  }
  // Every outer-layer stencil is one-sided: all of them must have switched to WLS.
  EXPECT_EQ(boundary_wls, boundary);
  // Information only: in 2-D a 0.3 dx jitter gives some full stencils ô_i > 0.12 (they switch
  // to WLS too, which is harmless: WLS is the more accurate operator).
  std::printf("D=%d: WLS rows %d of %d outer, %d of %d with full stencils\n", D, boundary_wls,
              boundary, deep_wls, deep);
  EXPECT_LT(err, 1e-10 * quadratic_laplacian<D>);
  ::testing::Test::RecordProperty("max_wls_error", std::to_string(err));
}

TEST(LddOperators, WlsQuadraticExactAtBoundary2D) {
  check_wls_quadratic_exact<2>(20);
}
TEST(LddOperators, WlsQuadraticExactAtBoundary3D) {
  check_wls_quadratic_exact<3>(8);
}

TEST(LddOperators, WlsEverywhereQuadraticExact3D) {
  auto c = make_cloud<3>(8, 0.3, LaplacianScheme::wls_everywhere);
  const auto f = sample<3>(c.x, [](const Vec<3>& p) { return quadratic<3>(p); });
  const auto lap = laplacian<3>(c.nb, c.ops, f);
  for (std::size_t i = 0; i < c.x.size(); ++i)
    ASSERT_NEAR(lap[i], quadratic_laplacian<3>, 1e-9) << "point " << i;
}

TEST(LddOperators, TikhonovOnAThinLine) {
  // Points on a line in 3-D: A_i has rank 1; B_i must be regularised, not infinite.
  std::vector<Vec<3>> x;
  for (int k = 0; k < 30; ++k) x.push_back(Vec<3>(0.01 * k, 0.0, 0.0));
  const auto nb = find_neighbours<3>(x, 0.025);
  OperatorOptions opt;
  opt.min_neighbours = 2;
  const auto ops = compute_operators<3>(x, nb, opt);
  for (std::size_t i = 0; i < x.size(); ++i) {
    ASSERT_FALSE(ops.isolated(static_cast<Index>(i)));
    EXPECT_TRUE(ops.flags[i] & op_degenerate);
    EXPECT_TRUE(ops.renormalisation[i].allFinite());
  }
  const auto sparse = compute_operators<3>(x, nb);  // N_min = 10 > 4 neighbours
  EXPECT_TRUE(sparse.isolated(5));
}

// ---- convergence ---------------------------------------------------------------------------

template <int D>
double smooth(const Vec<D>& p) {
  double f = std::sin(2.0 * p[0]) * std::cos(3.0 * p[1]);
  if constexpr (D == 3) f *= std::exp(0.5 * p[2]);
  return f;
}
template <int D>
Vec<D> smooth_gradient(const Vec<D>& p) {
  Vec<D> g;
  const double e = D == 3 ? std::exp(0.5 * p[D - 1]) : 1.0;
  g[0] = 2.0 * std::cos(2.0 * p[0]) * std::cos(3.0 * p[1]) * e;
  g[1] = -3.0 * std::sin(2.0 * p[0]) * std::sin(3.0 * p[1]) * e;
  if constexpr (D == 3) g[2] = 0.5 * smooth<D>(p);
  return g;
}
template <int D>
double smooth_laplacian(const Vec<D>& p) {
  return (-4.0 - 9.0 + (D == 3 ? 0.25 : 0.0)) * smooth<D>(p);
}

struct Errors {
  double gradient = 0.0, laplacian = 0.0;
};

/// RMS errors over the points at least h from the cloud's boundary (full stencils). RMS, not max:
/// the max over a jittered cloud grows with the number of points sampled (extreme values of the
/// stencil asymmetry) and hides the order.
template <int D>
Errors interior_errors(int cells, double jitter, LaplacianScheme scheme) {
  auto c = make_cloud<D>(cells, jitter, scheme, 11);
  const double h = 2.5 / cells;
  const auto f = sample<D>(c.x, [](const Vec<D>& p) { return smooth<D>(p); });
  const auto g = gradient<D>(c.x, c.nb, c.ops, f);
  const auto lap = laplacian<D>(c.nb, c.ops, f);
  Errors e;
  int count = 0;
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    if (test::depth_in_box<D>(c.x[i], c.lo, c.hi) < h) continue;
    e.gradient += (g[i] - smooth_gradient<D>(c.x[i])).squaredNorm();
    e.laplacian += std::pow(lap[i] - smooth_laplacian<D>(c.x[i]), 2);
    ++count;
  }
  e.gradient = std::sqrt(e.gradient / count);
  e.laplacian = std::sqrt(e.laplacian / count);
  return e;
}

template <int D>
void check_orders(std::vector<int> cells) {
  std::vector<double> dx, grad_jit, lap_wls_jit, lap_eq7_lattice, lap_eq7_jit;
  for (int n : cells) {
    dx.push_back(1.0 / n);
    const auto jw = interior_errors<D>(n, 0.3, LaplacianScheme::wls_everywhere);
    const auto je = interior_errors<D>(n, 0.3, LaplacianScheme::offset_vector);
    const auto le = interior_errors<D>(n, 0.0, LaplacianScheme::offset_vector);
    grad_jit.push_back(jw.gradient);
    lap_wls_jit.push_back(jw.laplacian);
    lap_eq7_jit.push_back(je.laplacian);
    lap_eq7_lattice.push_back(le.laplacian);
    std::printf("D=%d n=%d  grad(jit) %.3e  lapWLS(jit) %.3e  lap7(lattice) %.3e  lap7(jit) %.3e\n",
                D, n, jw.gradient, jw.laplacian, le.laplacian, je.laplacian);
  }
  const double p_grad = test::observed_order(dx, grad_jit);
  const double p_wls = test::observed_order(dx, lap_wls_jit);
  const double p_eq7 = test::observed_order(dx, lap_eq7_lattice);
  const double p_eq7_jit = test::observed_order(dx, lap_eq7_jit);
  std::printf(
      "D=%d orders: gradient %.2f, WLS Laplacian %.2f, eq.7 lattice %.2f, eq.7 jittered %.2f\n", D,
      p_grad, p_wls, p_eq7, p_eq7_jit);
  // Eq. 6 is exact for linear fields only; on an irregular stencil the quadratic Taylor term
  // leaves an O(h) error: expected order 1.
  EXPECT_GT(p_grad, 1.0 - 0.1);
  // WLS is exact for quadratics; the cubic term divided by h² leaves O(h): expected order 1.
  EXPECT_GT(p_wls, 1.0 - 0.1);
  // Eq. 7 on a lattice: the stencil is symmetric, odd moments vanish, and the isotropic moments
  // make it exact for quadratics; the quartic term leaves O(h²): expected order 2.
  EXPECT_GT(p_eq7, 2.0 - 0.1);
  // Eq. 7 on a cloud jittered by a fixed fraction of dx is not consistent for general
  // quadratics (spec §1.7.2): its error does not fall with h. This documents why WLS exists.
  EXPECT_LT(p_eq7_jit, 0.5);
}

TEST(LddOperators, ConvergenceOrders2D) {
  check_orders<2>({16, 32, 64});
}
TEST(LddOperators, ConvergenceOrders3D) {
  check_orders<3>({10, 14, 20});
}

}  // namespace
}  // namespace hm::ldd
