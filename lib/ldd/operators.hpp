#pragma once
// Discrete operators of LDD (spec §1.7, the paper's eqs. 6–9), per point i over N_i, r_ij = r_j −
// r_i, W_ij = W(|r_ij|/h) (Wendland C2):
//   A_i = Σ W_ij r_ij ⊗ r_ij,  B_i = A_i⁻¹ (eq. 8),  o_i = Σ W_ij r_ij (eq. 9)
//   gradient (eq. 6)   ⟨∇f⟩_i = B_i Σ W_ij r_ij (f_j − f_i)       exact for linear f
//   divergence         ⟨∇·u⟩_i = Σ (W_ij B_i r_ij)·(u_j − u_i)
//   Laplacian (eq. 7)  ⟨∇²f⟩_i = Σ c_ij (f_j − f_i),  c_ij = 2d W_ij (1 − r_ij·B_i o_i) / D_i,
//                      D_i = Σ W_ij (1 − r_ij·B_i o_i)|r_ij|²   exact for linear f and |r|²
// Eq. 7 is exact for general quadratics only on isotropic stencils; on one-sided stencils (walls,
// free surface) it has an O(1) error and negative c_ij. There the row uses the second-order
// weighted-least-squares Laplacian (GFDM/LSMPS): fit f_j − f_i ≈ r·∇f + ½ rᵀHr with weights W_ij,
// ∇² = tr H, exact for every quadratic on any stencil whose moment matrix is regular.
// Ill-conditioned B_i (§1.7.4): λ_min of M_i = d A_i / tr A_i below λ_c → Tikhonov
// B_i = (A_i + λ_c tr(A_i)/d I)⁻¹ and the point is flagged `degenerate` (a surface indicator).
// Fewer than N_min neighbours → `isolated`: no operators (all coefficients zero).
#include <span>
#include <vector>

#include "ldd/neighbours.hpp"

namespace hm::ldd {

/// Which rows get the second-order WLS Laplacian instead of eq. 7.
enum class LaplacianScheme : std::uint8_t {
  offset_vector,     ///< eq. 7 everywhere
  wls_where_needed,  ///< WLS where eq. 7 has a negative c_ij or the stencil is one-sided (default)
  wls_everywhere,    ///< WLS everywhere
};

struct OperatorOptions {
  double lambda_c = 0.05;  ///< λ_c: conditioning threshold of M_i (§1.7.4)
  int min_neighbours = 0;  ///< N_min; 0 = the spec's default, 4 (2-D) or 10 (3-D)
  /// ô_i above this marks a one-sided stencil that gets the WLS Laplacian. Jittered (0.3 dx)
  /// interior stencils reach ≈ 0.06–0.1, half-space stencils 0.24–0.36; below τ_o = 0.2 of §1.8 so
  /// that the second layer under a surface is caught too.
  double one_sided_offset = 0.12;
  LaplacianScheme laplacian = LaplacianScheme::wls_where_needed;
  /// Rows with |Σc_ij| / Σ|c_ij| below this (weak diagonal), and eq. 7 rows with negative
  /// weights whose WLS fit failed, take the clamped eq. 7; 0 disables (the flow solver uses 0.3).
  double min_dominance = 0.0;
};

/// Flags of a point's operators (bit set).
enum OperatorFlag : std::uint8_t {
  op_isolated = 1,    ///< fewer than N_min neighbours: no operators
  op_degenerate = 2,  ///< λ_min(M_i) < λ_c: Tikhonov-regularised B_i
  op_wls = 4,         ///< Laplacian row from the second-order WLS fit
  op_negative = 8,    ///< eq. 7 had a negative weight on this stencil
  op_clamped = 16,    ///< Laplacian row from eq. 7 with weights clamped at 0 (weak diagonal)
};

template <int D>
struct Operators {
  double radius = 0.0;                  ///< h [m]
  std::vector<Mat<D>> renormalisation;  ///< B_i [1/m²]
  std::vector<Vec<D>> offset;           ///< o_i [m]
  std::vector<double> number_density;   ///< n_i = Σ W_ij
  std::vector<double> offset_ratio;     ///< ô_i = |o_i| / Σ W_ij |r_ij| ∈ [0, 1]
  std::vector<double> lambda_min;       ///< smallest eigenvalue of M_i (1 for isotropic)
  std::vector<std::uint8_t> flags;      ///< OperatorFlag bits
  std::vector<double> laplacian;        ///< c_ij [1/m²], aligned with Neighbours::indices
  /// Quadrature weight ω_j of each point in every sum over neighbours (empty: all 1). A wall node
  /// stands for the wall measure it samples, ω = measure / dx^(D−1) (wall_node_weights): the
  /// wall's share of the moments then does not grow with the wall-node density.
  std::vector<double> weight;

  bool isolated(Index i) const { return flags[i] & op_isolated; }
  double weight_of(Index j) const { return weight.empty() ? 1.0 : weight[j]; }
};

/// Computes the operators of every point from the neighbour lists; OpenMP parallel.
/// `weight`: ω per point (Operators::weight), empty = all 1.
template <int D>
Operators<D> compute_operators(std::span<const Vec<D>> positions, const Neighbours& neighbours,
                               const OperatorOptions& options = {},
                               std::span<const double> weight = {});

/// Gradient coefficient g_ij = ω_j W_ij B_i r_ij of pair (i, j) [1/m].
template <int D>
inline Vec<D> gradient_weight(const Operators<D>& ops, Index i, Index j, const Vec<D>& r_ij) {
  return ops.weight_of(j) * wendland_c2(r_ij.norm() / ops.radius) * (ops.renormalisation[i] * r_ij);
}

/// ⟨∇f⟩_i of eq. 6 for every point (zero at isolated points).
template <int D>
std::vector<Vec<D>> gradient(std::span<const Vec<D>> positions, const Neighbours& neighbours,
                             const Operators<D>& ops, std::span<const double> f);

/// ⟨∇·u⟩_i for every point (zero at isolated points).
template <int D>
std::vector<double> divergence(std::span<const Vec<D>> positions, const Neighbours& neighbours,
                               const Operators<D>& ops, std::span<const Vec<D>> u);

/// ⟨∇u⟩_i, (∇u)_ab = ∂u_a/∂x_b, of eq. 6 for every fluid point (zero at isolated points and
/// wall nodes, whose rows of the PPE and whose motion need none of it), with the
/// walls seen as slip walls: across a wall node j only the normal part of the velocity
/// difference counts, u_j − u_i → n_j n_j·(u_j − u_i) [CHOICE]. The wall node carries the
/// no-penetration condition; its tangential velocity is the no-slip condition of the viscous
/// term only. With the full difference a fluid film sliding at U over nodes at rest had a
/// divergence of order U/dx wherever the wall nodes under it were not symmetric (at the edge of
/// the wetted floor), and the PPE turned that into kPa pressures that drove the tip of the K&O
/// dam break at L/40 to 5 m/s (the Ritter limit 2√(gH) is 3.4 m/s).
template <int D>
std::vector<Mat<D>> slip_velocity_gradient(const PointSet<D>& points, const Neighbours& neighbours,
                                           const Operators<D>& ops, std::span<const Vec<D>> u);

/// ⟨∇²f⟩_i = Σ c_ij (f_j − f_i) for every point (zero at isolated points).
template <int D>
std::vector<double> laplacian(const Neighbours& neighbours, const Operators<D>& ops,
                              std::span<const double> f);

}  // namespace hm::ldd
