#include "rbf/interpolator.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/CholmodSupport>

#include "core/errors.hpp"
#include "rbf/wendland.hpp"

namespace hm::rbf {
namespace {

using RowSparse = Eigen::SparseMatrix<double, Eigen::RowMajor, Eigen::Index>;
using ColSparse = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

std::string format_point(const Points& x, Eigen::Index i) {
  std::string s = "(";
  for (Eigen::Index k = 0; k < x.cols(); ++k) s += fmt::format("{}{:.6g}", k ? ", " : "", x(i, k));
  return s + ")";
}

void check_points(const Points& source, const Points& target) {
  if (source.rows() == 0)
    input_error(
        "RBF mapping: the source point set is empty; expected at least one source point "
        "(the structure's surface nodes)");
  if (source.cols() != 2 && source.cols() != 3)
    input_error("RBF mapping: source points have {} coordinates; expected 2 or 3", source.cols());
  if (target.cols() != source.cols())
    input_error(
        "RBF mapping: source points have {} coordinates but target points {}; expected "
        "both 2-D or both 3-D",
        source.cols(), target.cols());
  if (!source.allFinite() || !target.allFinite())
    input_error(
        "RBF mapping: {} point coordinates are not finite (NaN or inf); expected finite "
        "coordinates in metres",
        source.allFinite() ? "target" : "source");
}

// A target box ~1000 times larger or smaller than the source box is almost surely a unit slip.
void check_units(const Points& source, const Points& target) {
  const double ds = bounding_box_diagonal(source), dt = bounding_box_diagonal(target);
  if (ds <= 0 || dt <= 0) return;
  const double ratio = dt / ds;
  const bool about_1000 =
      (ratio > 1000.0 / 3 && ratio < 3000.0) || (ratio < 3.0 / 1000 && ratio > 1.0 / 3000);
  if (about_1000)
    input_error(
        "RBF mapping: the target bounding box ({:.4g} m diagonal) is {:.4g} times the "
        "source bounding box ({:.4g} m diagonal): units differ by ~1000? (mm vs m); "
        "expected both point sets in metres",
        dt, ratio, ds);
}

// Row i: φ(|x_i − s_j|/δ) for every source s_j within δ, columns sorted. Parallel over rows.
RowSparse kernel_matrix(const Points& at, const PointTree& sources, double delta) {
  const Eigen::Index n = at.rows();
  std::vector<std::vector<std::pair<Eigen::Index, double>>> rows(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVectorXd x = at.row(i);
    auto found = sources.within(x.data(), delta);
    std::sort(found.begin(), found.end());
    for (auto& f : found) f.second = wendland_c2(f.second / delta);
    rows[i] = std::move(found);
  }
  RowSparse m(n, sources.points().rows());
  Eigen::Index nnz = 0;
  for (const auto& r : rows) nnz += static_cast<Eigen::Index>(r.size());
  m.resizeNonZeros(nnz);
  Eigen::Index k = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    m.outerIndexPtr()[i] = k;
    for (const auto& [j, v] : rows[i]) {
      m.innerIndexPtr()[k] = j;
      m.valuePtr()[k++] = v;
    }
    std::vector<std::pair<Eigen::Index, double>>().swap(rows[i]);
  }
  m.outerIndexPtr()[n] = k;
  return m;
}

}  // namespace

struct RbfInterpolator::Impl {
  RbfOptions options;
  Points source_raw;
  Normalisation norm;
  std::unique_ptr<PointTree> tree;  // normalised sources
  double spacing = 0;               // normalised
  double delta = 0;                 // normalised
  Eigen::VectorXd target_distance;  // normalised distance of each target to the nearest source
  LinearBasis basis;
  Eigen::MatrixXd P_s, P_t, W;                               // W = Φ⁻¹ P_s
  ColSparse Phi;                                             // Φ_ss
  RowSparse Phi_ts;                                          // target–source kernel
  Eigen::CholmodSupernodalLLT<ColSparse, Eigen::Lower> llt;  // supernodal: ~3× Simplicial
  Eigen::LLT<Eigen::MatrixXd> schur;                         // S = P_sᵀ Φ⁻¹ P_s

  void measure_spacing();
  void choose_support();
  void measure_target_distances(const Points& target_n);
  void factorise();
  // Solves [Φ P; Pᵀ 0][a; b] = [z; g].
  std::pair<Eigen::MatrixXd, Eigen::MatrixXd> solve(const Eigen::MatrixXd& z,
                                                    const Eigen::MatrixXd& g) const;
};

void RbfInterpolator::Impl::measure_spacing() {
  const Points& x = tree->points();
  const Eigen::Index n = x.rows();
  if (n < 2) {
    spacing = 1.0;  // a single source point: the box is normalised to 1
    return;
  }
  double sum = 0;
  Eigen::Index duplicate = -1, duplicate_of = -1;
#pragma omp parallel for reduction(+ : sum)
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVectorXd p = x.row(i);
    const auto nn = tree->nearest_k(p.data(), 2);
    const auto& other = nn[0].first == i ? nn[1] : nn[0];
    if (other.second == 0.0) {
#pragma omp critical
      if (duplicate < 0 || i < duplicate) {
        duplicate = i;
        duplicate_of = other.first;
      }
    }
    sum += other.second;
  }
  if (duplicate >= 0)
    input_error(
        "RBF mapping: source points {} and {} coincide at {} m; expected distinct source "
        "points (merge duplicate nodes)",
        std::min(duplicate, duplicate_of), std::max(duplicate, duplicate_of),
        format_point(source_raw, duplicate));
  spacing = sum / static_cast<double>(n);
}

void RbfInterpolator::Impl::choose_support() {
  if (options.support_radius > 0) {
    delta = options.support_radius / norm.scale;
    return;
  }
  if (!(options.support_factor > 0))
    input_error("RBF mapping: support_factor = {}; expected a value > 0", options.support_factor);
  delta = options.support_factor * spacing;
}

void RbfInterpolator::Impl::measure_target_distances(const Points& target_n) {
  target_distance.resize(target_n.rows());
#pragma omp parallel for
  for (Eigen::Index i = 0; i < target_n.rows(); ++i) {
    const Eigen::RowVectorXd p = target_n.row(i);
    target_distance[i] = tree->nearest(p.data()).second;
  }
  if (options.allow_distant_targets || target_n.rows() == 0) return;
  const Eigen::Index beyond = (target_distance.array() > delta).count();
  if (beyond == 0) return;
  Eigen::Index worst = 0;
  target_distance.maxCoeff(&worst);
  const Points worst_point = target_n.row(worst) * norm.scale + norm.centre;
  input_error(
      "RBF mapping: {} of {} target points lie farther than the support radius {:.4g} m "
      "from every source point (worst: target {} at {} m, {:.4g} m away = {:.1f} source "
      "spacings); the source and target meshes do not overlap: check the geometry's "
      "position, orientation and units",
      beyond, target_n.rows(), delta * norm.scale, worst, format_point(worst_point, 0),
      target_distance[worst] * norm.scale, target_distance[worst] / spacing);
}

void RbfInterpolator::Impl::factorise() {
  Phi = kernel_matrix(tree->points(), *tree, delta);
  llt.compute(Phi);
  if (llt.info() != Eigen::Success)
    numerical_error(
        "RBF mapping: the Cholesky factorisation of the {}×{} Wendland matrix failed "
        "(support radius {:.4g} m); the source points may be nearly coincident",
        Phi.rows(), Phi.cols(), delta * norm.scale);
  basis = LinearBasis(tree->points());
  P_s = basis.evaluate(tree->points());
  W = llt.solve(P_s);
  schur.compute(P_s.transpose() * W);
  if (schur.info() != Eigen::Success)
    numerical_error("RBF mapping: the polynomial constraint matrix is singular ({} terms)",
                    basis.size());
}

std::pair<Eigen::MatrixXd, Eigen::MatrixXd> RbfInterpolator::Impl::solve(
    const Eigen::MatrixXd& z, const Eigen::MatrixXd& g) const {
  const Eigen::MatrixXd a0 = llt.solve(z);
  const Eigen::MatrixXd b = schur.solve(P_s.transpose() * a0 - g);
  return {a0 - W * b, b};
}

RbfInterpolator::RbfInterpolator(const Points& source, const Points& target, RbfOptions options)
    : impl_(std::make_unique<Impl>()) {
  check_points(source, target);
  check_units(source, target);
  Impl& m = *impl_;
  m.options = options;
  m.source_raw = source;
  m.norm = bounding_box_normalisation(source);
  m.tree = std::make_unique<PointTree>(m.norm.apply(source));
  m.measure_spacing();
  m.choose_support();
  const Points target_n = m.norm.apply(target);
  m.measure_target_distances(target_n);
  m.factorise();
  m.P_t = m.basis.evaluate(target_n);
  m.Phi_ts = kernel_matrix(target_n, *m.tree, m.delta);
}

RbfInterpolator::~RbfInterpolator() = default;
RbfInterpolator::RbfInterpolator(RbfInterpolator&&) noexcept = default;
RbfInterpolator& RbfInterpolator::operator=(RbfInterpolator&&) noexcept = default;

Eigen::Index RbfInterpolator::source_count() const {
  return impl_->Phi.rows();
}
Eigen::Index RbfInterpolator::target_count() const {
  return impl_->Phi_ts.rows();
}
double RbfInterpolator::support_radius() const {
  return impl_->delta * impl_->norm.scale;
}
double RbfInterpolator::source_spacing() const {
  return impl_->spacing * impl_->norm.scale;
}

Eigen::MatrixXd RbfInterpolator::apply(const Eigen::MatrixXd& source_fields) const {
  const Impl& m = *impl_;
  if (source_fields.rows() != m.Phi.rows())
    input_error("RBF mapping: field has {} rows; expected one per source point ({})",
                source_fields.rows(), m.Phi.rows());
  const auto [a, b] =
      m.solve(source_fields, Eigen::MatrixXd::Zero(m.P_s.cols(), source_fields.cols()));
  return m.Phi_ts * a + m.P_t * b;
}

Eigen::MatrixXd RbfInterpolator::apply_transpose(const Eigen::MatrixXd& target_fields) const {
  const Impl& m = *impl_;
  if (target_fields.rows() != m.Phi_ts.rows())
    input_error("RBF mapping: field has {} rows; expected one per target point ({})",
                target_fields.rows(), m.Phi_ts.rows());
  const Eigen::MatrixXd z = m.Phi_ts.transpose() * target_fields;
  return m.solve(z, m.P_t.transpose() * target_fields).first;
}

namespace {

// λ_max/λ_min of the SPD kernel matrix by power and inverse-power iteration.
template <typename Solver>
double condition_estimate(const ColSparse& A, const Solver& llt) {
  Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(A.rows(), 1.0, 2.0).normalized();
  Eigen::VectorXd y = x;
  double lmax = 0, inv_lmin = 0;
  for (int it = 0; it < 50; ++it) {
    const Eigen::VectorXd ax = A * x;
    lmax = x.dot(ax);
    x = ax.normalized();
    const Eigen::VectorXd iy = llt.solve(y);
    inv_lmin = y.dot(iy);
    y = iy.normalized();
  }
  return lmax * inv_lmin;
}

}  // namespace

QualityReport RbfInterpolator::quality_report(const Eigen::MatrixXd& source_fields) const {
  const Impl& m = *impl_;
  QualityReport r;
  r.support_radius = support_radius();
  r.source_spacing = source_spacing();
  r.far_tolerance = m.options.far_factor * r.source_spacing;
  if (m.target_distance.size() > 0) {
    r.worst_target_distance = m.target_distance.maxCoeff(&r.worst_target) * m.norm.scale;
    r.far_targets = (m.target_distance.array() * m.norm.scale > r.far_tolerance).count();
  }
  r.polynomial_terms = m.basis.size();
  r.dropped_directions = m.basis.dropped();
  r.condition_estimate = condition_estimate(m.Phi, m.llt);
  r.mean_neighbours = static_cast<double>(m.Phi.nonZeros()) / static_cast<double>(m.Phi.rows());

  r.field_error = Eigen::VectorXd::Constant(source_fields.cols(), std::nan(""));
  const Eigen::Index n = m.source_raw.rows();
  if (source_fields.cols() == 0 || n < 20) return r;
  if (source_fields.rows() != n)
    input_error("RBF quality report: field has {} rows; expected one per source point ({})",
                source_fields.rows(), n);
  std::vector<Eigen::Index> kept, left_out;
  for (Eigen::Index i = 0; i < n; ++i) (i % 10 == 5 ? left_out : kept).push_back(i);
  RbfOptions o = m.options;
  o.support_radius = r.support_radius;
  o.allow_distant_targets = true;
  const RbfInterpolator sub(m.source_raw(kept, Eigen::all), m.source_raw(left_out, Eigen::all), o);
  const Eigen::MatrixXd predicted = sub.apply(source_fields(kept, Eigen::all));
  const Eigen::MatrixXd error = predicted - source_fields(left_out, Eigen::all);
  for (Eigen::Index k = 0; k < source_fields.cols(); ++k) {
    const double scale = source_fields.col(k).cwiseAbs().maxCoeff();
    const double e = error.col(k).cwiseAbs().maxCoeff();
    r.field_error[k] = scale > 0 ? e / scale : e;
  }
  return r;
}

}  // namespace hm::rbf
