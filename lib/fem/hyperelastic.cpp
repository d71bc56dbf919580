#include "fem/hyperelastic.hpp"

#include <cmath>

#include <Eigen/LU>

#include "core/errors.hpp"

namespace hm::fem {
namespace {

using Matrix3 = Eigen::Matrix3d;
using Voigt6 = Eigen::Matrix<double, 6, 6>;

constexpr int kVoigtI[6] = {0, 1, 2, 1, 0, 0};
constexpr int kVoigtJ[6] = {0, 1, 2, 2, 2, 1};

/// det(I + A) − 1 without the cancellation of forming I + A: the sum of the principal minors of A.
double det_minus_one(const Matrix3& a) {
  const double minors2 = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0) + a(0, 0) * a(2, 2) -
                         a(0, 2) * a(2, 0) + a(1, 1) * a(2, 2) - a(1, 2) * a(2, 1);
  return a.trace() + minors2 + a.determinant();
}

struct Law3 {
  Matrix3 stress = Matrix3::Zero();
  Voigt6 tangent = Voigt6::Zero();
  double energy = 0.0;
  double det_f = 1.0;
};

Law3 saint_venant_kirchhoff(const Lame& l, const Matrix3& e) {
  Law3 out;
  const double trace = e.trace();
  out.stress = l.lambda * trace * Matrix3::Identity() + 2.0 * l.mu * e;
  out.energy = 0.5 * l.lambda * trace * trace + l.mu * e.squaredNorm();
  out.tangent.topLeftCorner<3, 3>().setConstant(l.lambda);
  out.tangent.topLeftCorner<3, 3>().diagonal().array() += 2.0 * l.mu;
  out.tangent.bottomRightCorner<3, 3>().diagonal().setConstant(l.mu);
  const double det_c = 1.0 + det_minus_one(2.0 * e);
  out.det_f = det_c > 0.0 ? std::sqrt(det_c) : -1.0;
  return out;
}

Law3 neo_hookean(const Lame& l, const Matrix3& e) {
  Law3 out;
  const double det_c_minus_one = det_minus_one(2.0 * e);
  if (!(det_c_minus_one > -1.0)) {
    out.det_f = -1.0;
    return out;
  }
  const double log_j = 0.5 * std::log1p(det_c_minus_one);
  out.det_f = std::exp(log_j);
  const Matrix3 ci = (Matrix3::Identity() + 2.0 * e).inverse();
  // S = μ (I − C⁻¹) + λ ln J C⁻¹ = C⁻¹ (2μE + λ ln J I): no cancellation at small strain.
  out.stress = ci * (2.0 * l.mu * e + l.lambda * log_j * Matrix3::Identity());
  out.stress = 0.5 * (out.stress + out.stress.transpose()).eval();
  out.energy = l.mu * e.trace() - l.mu * log_j + 0.5 * l.lambda * log_j * log_j;
  // ℂ = λ C⁻¹⊗C⁻¹ + 2(μ − λ ln J) 𝕀_{C⁻¹},  𝕀_ijkl = ½(C⁻¹_ik C⁻¹_jl + C⁻¹_il C⁻¹_jk).
  const double s = l.mu - l.lambda * log_j;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) {
      const int i = kVoigtI[a], j = kVoigtJ[a], k = kVoigtI[b], m = kVoigtJ[b];
      out.tangent(a, b) =
          l.lambda * ci(i, j) * ci(k, m) + s * (ci(i, k) * ci(j, m) + ci(i, m) * ci(j, k));
    }
  return out;
}

Law3 evaluate3(const HyperelasticModel& model, const Lame& lame, const Matrix3& e) {
  return model.law == MaterialLaw::neo_hookean ? neo_hookean(lame, e)
                                               : saint_venant_kirchhoff(lame, e);
}

/// The 3-D E of a 2-D section: E33 = 0 (plane strain) or the strain that frees S33 (plane
/// stress, found by Newton on E33 with dS33/dE33 = ℂ_3333).
Law3 section_law(const HyperelasticModel& model, const Lame& lame, const Eigen::Matrix2d& e2) {
  Matrix3 e = Matrix3::Zero();
  e.topLeftCorner<2, 2>() = e2;
  Law3 law = evaluate3(model, lame, e);
  if (model.elastic.plane == PlaneAssumption::plane_strain) return law;
  for (int iteration = 0; iteration < 50 && law.det_f > 0.0; ++iteration) {
    const double scale = std::abs(law.tangent(2, 2)) + 1e-300;
    if (std::abs(law.stress(2, 2)) <= 1e-14 * scale) break;
    const double step = -law.stress(2, 2) / law.tangent(2, 2);
    double next = e(2, 2) + step;
    // Keep the through-thickness stretch positive: C33 = 1 + 2 E33 > 0.
    if (next <= -0.5) next = 0.5 * (e(2, 2) - 0.5);
    e(2, 2) = next;
    law = evaluate3(model, lame, e);
  }
  return law;
}

/// In-plane Voigt indices (xx, yy, xy) within the 6-vector.
constexpr int kPlane[3] = {0, 1, 5};

template <int D>
MaterialPoint<D> reduce(const HyperelasticModel& model, const Law3& law) {
  MaterialPoint<D> out;
  out.energy = law.energy;
  out.det_f = law.det_f;
  if constexpr (D == 3) {
    out.stress = law.stress;
    out.tangent = law.tangent;
  } else {
    out.stress = law.stress.topLeftCorner<2, 2>();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) out.tangent(a, b) = law.tangent(kPlane[a], kPlane[b]);
    if (model.elastic.plane == PlaneAssumption::plane_stress)  // condense the free E33
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
          out.tangent(a, b) -=
              law.tangent(kPlane[a], 2) * law.tangent(2, kPlane[b]) / law.tangent(2, 2);
  }
  return out;
}

}  // namespace

const char* to_string(MaterialLaw law) {
  return law == MaterialLaw::neo_hookean ? "neo_hookean" : "saint_venant_kirchhoff";
}

MaterialLaw material_law_from(std::string_view name, std::string_view context) {
  if (name == "saint_venant_kirchhoff") return MaterialLaw::saint_venant_kirchhoff;
  if (name == "neo_hookean") return MaterialLaw::neo_hookean;
  input_error(
      "{} = \"{}\" is not a material law; accepted: \"saint_venant_kirchhoff\", "
      "\"neo_hookean\"",
      context, name);
}

void validate(const HyperelasticModel& model, int dim, std::string_view context) {
  const double nu = model.elastic.material.poisson_ratio;
  if (model.law == MaterialLaw::neo_hookean && !(nu < 0.5))
    input_error(
        "{}: Poisson's ratio ν = {} is invalid for the compressible neo-Hookean law; it must "
        "lie in (-1, 0.5) (use ν ≤ 0.49 for rubber)",
        context, nu);
  validate(model.elastic, dim, context);
}

Lame::Lame(const Material& m) {
  const double e = m.youngs_modulus_pa, nu = m.poisson_ratio;
  lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
  mu = e / (2 * (1 + nu));
}

template <int D>
MaterialPoint<D> evaluate_law(const HyperelasticModel& model, const Lame& lame,
                              const Eigen::Matrix<double, D, D>& e) {
  if constexpr (D == 3)
    return reduce<3>(model, evaluate3(model, lame, e));
  else
    return reduce<2>(model, section_law(model, lame, e));
}

template <int D>
double strain_energy_density(const HyperelasticModel& model, const Lame& lame,
                             const Eigen::Matrix<double, D, D>& e) {
  if constexpr (D == 3)
    return evaluate3(model, lame, e).energy;
  else
    return section_law(model, lame, e).energy;
}

template MaterialPoint<2> evaluate_law<2>(const HyperelasticModel&, const Lame&,
                                          const Eigen::Matrix2d&);
template MaterialPoint<3> evaluate_law<3>(const HyperelasticModel&, const Lame&,
                                          const Eigen::Matrix3d&);
template double strain_energy_density<2>(const HyperelasticModel&, const Lame&,
                                         const Eigen::Matrix2d&);
template double strain_energy_density<3>(const HyperelasticModel&, const Lame&,
                                         const Eigen::Matrix3d&);

}  // namespace hm::fem
