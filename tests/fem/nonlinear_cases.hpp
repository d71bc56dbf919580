#pragma once
// Benchmark structures of the nonlinear solver tests and benchmarks: the elastica strip under a
// follower end moment and the Turek–Hron CSM flag clamped on its cylinder.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/hyperelastic_body.hpp"
#include "fem/nonlinear_static.hpp"
#include "mesh/structured.hpp"

namespace hm::fem::test {

/// Index of the mesh node nearest to `point`.
inline Eigen::Index nearest_node(const mesh::StructureMesh& m, const Eigen::VectorXd& point) {
  Eigen::Index best = 0;
  (m.nodes.rowwise() - point.transpose()).rowwise().squaredNorm().minCoeff(&best);
  return best;
}

/// A pure end moment M [N·m per the section's thickness] on the facets of group `face` of a
/// 2-D body, turning with the end: the consistent nodal forces f⁰ of the beam's linear bending
/// stress σ = −M (Y − Y_c)/I on the reference face (I = h³/12 of its height h), rotated by the
/// angle φ the face's chord (bottom corner → top corner) has turned, f = R(φ) f⁰. Its net force
/// is exactly zero at any deformation. (A traction along the face's current normal is not: the
/// face bows slightly, ∫σ n̂ dY ≠ 0, and on a strip of L/h = 100 that stray force's lever arm
/// bends the strip 0.5 % further than the moment alone.)
class FollowerMoment {
 public:
  FollowerMoment(const mesh::StructureMesh& m, const std::string& face, double moment,
                 double thickness)
      : reference_force_(Eigen::VectorXd::Zero(2 * m.node_count())) {
    const auto& facets = m.facet_groups.at(face);
    double y_min = 1e300, y_max = -1e300;
    for (Eigen::Index f : facets)
      for (int k = 0; k < 3; ++k) {
        const Eigen::Index node = m.facets(f, k);
        if (m.nodes(node, 1) < y_min) y_min = m.nodes(node, 1), bottom_ = node;
        if (m.nodes(node, 1) > y_max) y_max = m.nodes(node, 1), top_ = node;
      }
    const double h = y_max - y_min, centre = 0.5 * (y_min + y_max);
    const double stress_per_y = -moment / (h * h * h / 12.0);
    const Eigen::Vector2d centroid = m.nodes.colwise().mean().transpose();
    // line3: ends 0, 1 and middle 2 at s = 0, 1, ½; three Gauss points.
    auto n = [](double s) {
      return Eigen::Vector3d((1 - s) * (1 - 2 * s), s * (2 * s - 1), 4 * s * (1 - s));
    };
    auto dn = [](double s) { return Eigen::Vector3d(4 * s - 3, 4 * s - 1, 4 - 8 * s); };
    const double gauss[3] = {0.5 - std::sqrt(0.15), 0.5, 0.5 + std::sqrt(0.15)};
    const double weight[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
    for (Eigen::Index f : facets) {
      Eigen::Matrix<double, 3, 2> x0;
      for (int k = 0; k < 3; ++k) x0.row(k) = m.nodes.row(m.facets(f, k));
      for (int q = 0; q < 3; ++q) {
        const double s = gauss[q];
        const Eigen::Vector2d tangent = x0.transpose() * dn(s);
        Eigen::Vector2d normal(tangent.y(), -tangent.x());  // |normal| = |dX/ds|
        if (normal.dot(x0.row(2).transpose() - centroid) < 0) normal = -normal;  // outward
        const double sigma = stress_per_y * (n(s).dot(x0.col(1)) - centre);
        for (int a = 0; a < 3; ++a)
          reference_force_.segment<2>(2 * m.facets(f, a)) +=
              thickness * weight[q] * n(s)[a] * sigma * normal;
      }
    }
    chord0_ = (m.nodes.row(top_) - m.nodes.row(bottom_)).transpose();
  }

  Eigen::VectorXd force(const Eigen::VectorXd& u) const {
    const Eigen::Matrix2d r = rotation(angle(u));
    Eigen::VectorXd f = reference_force_;
    for (Eigen::Index i = 0; i < f.size() / 2; ++i) f.segment<2>(2 * i) = r * f.segment<2>(2 * i);
    return f;
  }

  /// ∂f/∂u = R′(φ) f⁰ ⊗ ∂φ/∂u, φ depending on the two corners only.
  Eigen::SparseMatrix<double> stiffness(const Eigen::VectorXd& u) const {
    const Eigen::Vector2d c = chord(u);
    const Eigen::Vector2d dphi = Eigen::Vector2d(-c.y(), c.x()) / c.squaredNorm();  // ∂φ/∂(top)
    Eigen::Matrix2d turn;
    turn << 0, -1, 1, 0;
    const Eigen::Matrix2d dr = rotation(angle(u)) * turn;
    std::vector<Eigen::Triplet<double>> entries;
    for (Eigen::Index i = 0; i < reference_force_.size() / 2; ++i) {
      const Eigen::Vector2d df = dr * reference_force_.segment<2>(2 * i);
      if (df.isZero(0.0)) continue;
      for (int r = 0; r < 2; ++r)
        for (int k = 0; k < 2; ++k) {
          entries.emplace_back(static_cast<int>(2 * i + r), static_cast<int>(2 * top_ + k),
                               df[r] * dphi[k]);
          entries.emplace_back(static_cast<int>(2 * i + r), static_cast<int>(2 * bottom_ + k),
                               -df[r] * dphi[k]);
        }
    }
    Eigen::SparseMatrix<double> out(u.size(), u.size());
    out.setFromTriplets(entries.begin(), entries.end());
    return out;
  }

 private:
  Eigen::Vector2d chord(const Eigen::VectorXd& u) const {
    return chord0_ + u.segment<2>(2 * top_) - u.segment<2>(2 * bottom_);
  }
  double angle(const Eigen::VectorXd& u) const {
    const Eigen::Vector2d c = chord(u);
    return std::atan2(chord0_.x() * c.y() - chord0_.y() * c.x(), chord0_.dot(c));
  }
  static Eigen::Matrix2d rotation(double phi) {
    Eigen::Matrix2d r;
    r << std::cos(phi), -std::sin(phi), std::sin(phi), std::cos(phi);
    return r;
  }

  Eigen::VectorXd reference_force_;
  Eigen::Index top_ = 0, bottom_ = 0;
  Eigen::Vector2d chord0_;
};

/// The Turek–Hron flag: 0.35 × 0.02 m behind the cylinder of radius 0.05 m at (0.2, 0.2), its
/// left end clamped on the cylinder's arc (group "xmin"). A structured nx × ny tri6 mesh of the
/// unit strip mapped so that x runs from the arc to 0.6 m on every line y = const (the
/// mid-edge nodes mapped too: the cells along the arc are curved).
inline mesh::StructureMesh turek_hron_flag(int nx, int ny) {
  mesh::StructureMesh m = mesh::structured_rectangle(1.0, 0.02, nx, ny, Eigen::Vector2d(0.0, 0.19));
  for (Eigen::Index i = 0; i < m.node_count(); ++i) {
    const double y = m.nodes(i, 1);
    const double left = 0.2 + std::sqrt(0.05 * 0.05 - (y - 0.2) * (y - 0.2));
    m.nodes(i, 0) = left + m.nodes(i, 0) * (0.6 - left);
  }
  return m;
}

/// CSM material: ρ = 1000 kg/m³, ν = 0.4, μ = 0.5 MPa (E = 1.4 MPa), plane strain, StVK.
inline HyperelasticModel turek_hron_material() {
  return {{{1.4e6, 0.4, 1000.0}, PlaneAssumption::plane_strain, 1.0},
          MaterialLaw::saint_venant_kirchhoff};
}

}  // namespace hm::fem::test
