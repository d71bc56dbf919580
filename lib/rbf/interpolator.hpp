#pragma once
// RBF mapping between non-matching point sets: fields given on SOURCE points (the structure's
// surface nodes) are interpolated to TARGET points (vertices of a fluid wall mesh), 2-D or 3-D.
//
// Interpolant (in coordinates normalised by the source bounding box, point_cloud.hpp):
//   s(x) = Σ_j α_j φ(|x − x_j|/δ) + Σ_k β_k p_k(x),   φ = Wendland C2 (wendland.hpp),
// p = {1, linear terms in the directions spanned by the sources} (polynomial.hpp), with
//   [Φ  P] [α]   [u]
//   [Pᵀ 0] [β] = [0].
// Φ is sparse SPD; the saddle-point system is solved through the Schur complement
// S = Pᵀ Φ⁻¹ P (Φ by sparse supernodal Cholesky, CHOLMOD; S dense m × m, m ≤ 4). Constant and
// linear fields (rigid motions, every affine field) are reproduced exactly, and on target = source
// the map is the identity.
//
// Operator H (n_target × n_source): u_target = H u_source, evaluated on demand (H itself is dense):
// one sparse Cholesky solve per field plus a sparse product with the target–source kernel matrix.
//
// Consistent vs conservative: displacements and mode shapes are mapped CONSISTENTLY,
// Φ_f = H Φ_s. Forces are mapped CONSERVATIVELY with the transpose, f_s = Hᵀ f_f, which keeps the
// virtual work of every mode:  Φ_fᵀ f_f = (H Φ_s)ᵀ f_f = Φ_sᵀ (Hᵀ f_f) = Φ_sᵀ f_s,
// so the generalised (modal) forces are the same whichever side they are computed on; because H
// reproduces constants and linear fields, total force and total moment are preserved as well.
//
// Support radius δ (rule): δ = support_factor × h, where h is the mean distance from a source
// point to its nearest other source point; support_factor defaults to 4 (≈ 50 neighbours per
// point on a surface in 3-D). RbfOptions::support_radius overrides it (metres).
//
// Accuracy: this default is STATIONARY (δ/h fixed), which keeps the matrix sparse and well
// conditioned (λ_max/λ_min ≈ 1e2) but saturates: refining the sources no longer reduces the error
// of non-affine fields. Measured for f = sin(2x + 0.5)·cos(1.5y) + z²/2 on the unit sphere:
// max relative error ≈ 2e-3 (factor 4), 3e-4 (6), 6e-5 (8), 2e-5 (10), almost independent of the
// number of sources (1000…16 000). With a FIXED support radius (override, non-stationary) the
// error converges fast (measured order ≈ 5 at δ = 0.4 on that sphere, tests/rbf) at the price of
// more neighbours per row. Affine fields are exact either way.
#include <memory>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "rbf/point_cloud.hpp"
#include "rbf/polynomial.hpp"

namespace hm::rbf {

struct RbfOptions {
  double support_factor = 4.0;  ///< δ = factor × mean nearest-neighbour spacing of the sources
  double support_radius = 0.0;  ///< m; > 0 overrides the rule above
  /// Targets farther than this many source spacings from every source point are counted in the
  /// quality report.
  double far_factor = 2.0;
  /// Targets with no source point within the support radius make the build throw InputError
  /// (disjoint meshes) unless this is set.
  bool allow_distant_targets = false;
};

struct QualityReport {
  double support_radius = 0;         ///< m
  double source_spacing = 0;         ///< m, mean nearest-neighbour distance of the sources
  double far_tolerance = 0;          ///< m, = far_factor × source_spacing
  Eigen::Index far_targets = 0;      ///< targets farther than far_tolerance from every source point
  Eigen::Index worst_target = -1;    ///< target farthest from the source cloud
  double worst_target_distance = 0;  ///< m, its distance to the nearest source point
  Eigen::Index polynomial_terms = 0;    ///< 1 + spanned directions
  Eigen::Index dropped_directions = 0;  ///< degenerate directions (flat / colinear sources)
  double condition_estimate = 0;        ///< λ_max/λ_min of the RBF block Φ (power iterations)
  double mean_neighbours = 0;           ///< nonzeros per row of Φ
  /// Per field (column): leave-some-out estimate of the interpolation error — every 10th source
  /// point is dropped, the rest interpolates to it; max |error| / max |field|.
  Eigen::VectorXd field_error;
};

class RbfInterpolator {
 public:
  /// source: n_s × d, target: n_t × d points [m], d = 2 or 3. Throws InputError for an empty
  /// source set, mismatched dimensions, duplicate source points, bounding boxes differing by
  /// ~1000 (mm vs m) and targets outside the reach of the sources (disjoint meshes).
  RbfInterpolator(const Points& source, const Points& target, RbfOptions options = {});
  ~RbfInterpolator();
  RbfInterpolator(RbfInterpolator&&) noexcept;
  RbfInterpolator& operator=(RbfInterpolator&&) noexcept;

  Eigen::Index source_count() const;
  Eigen::Index target_count() const;

  /// Consistent map: columns of source_fields (n_s × k) → n_t × k (displacements, modes).
  Eigen::MatrixXd apply(const Eigen::MatrixXd& source_fields) const;
  /// Conservative map Hᵀ: columns of target_fields (n_t × k, forces) → n_s × k.
  Eigen::MatrixXd apply_transpose(const Eigen::MatrixXd& target_fields) const;

  double support_radius() const;  ///< m
  double source_spacing() const;  ///< m

  /// Quality report; field_error is filled for the given source fields (may have 0 columns).
  QualityReport quality_report(const Eigen::MatrixXd& source_fields) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hm::rbf
