#pragma once
// Hyperelastic laws of the geometrically nonlinear (total-Lagrangian) structure, written in the
// Green–Lagrange strain E = (C − I)/2 and the right Cauchy–Green tensor C = FᵀF:
//
//   Saint Venant–Kirchhoff:  W = λ/2 (tr E)² + μ E:E,            S = λ tr(E) I + 2μ E
//   compressible neo-Hookean: W = μ/2 (I₁ − 3) − μ ln J + λ/2 (ln J)²,
//                             S = μ (I − C⁻¹) + λ ln J C⁻¹,        J = det F = √det C
//
// with the Lamé constants of the linear material (λ = Eν/((1+ν)(1−2ν)), μ = E/(2(1+ν))), so both
// laws reduce to linear elasticity at small strain. StVK is exact for small strain with large
// rotation (the structures of this tool); neo-Hookean stays physical in compression and is the
// law for rubber near incompressibility (ν up to 0.49; ν → 0.5 locks and is refused).
//
// Voigt notation as in material.hpp: stress (S11, S22, S33, S23, S13, S12) and engineering
// strain (E11, E22, E33, 2E23, 2E13, 2E12); in 2-D (S11, S22, S12) and (E11, E22, 2E12). The
// tangent is the Voigt matrix of ℂ = ∂S/∂E. 2-D plane strain takes C33 = 1; plane stress finds
// E33 such that S33 = 0 (Newton, exact in one step for StVK) and condenses the tangent.
// The laws take E, not C: E = sym H + ½HᵀH from the displacement gradient H keeps its digits at
// small strain, where C − I would lose them (a 1e-14 strain would come out as round-off).
// Units: Pa (stress, tangent), J/m³ (energy density per reference volume).
#include <cstdint>
#include <string_view>

#include <Eigen/Core>

#include "fem/material.hpp"

namespace hm::fem {

enum class MaterialLaw : std::uint8_t { saint_venant_kirchhoff, neo_hookean };
const char* to_string(MaterialLaw law);
/// "saint_venant_kirchhoff" | "neo_hookean"; InputError naming `context` otherwise.
MaterialLaw material_law_from(std::string_view name, std::string_view context);

/// A material law with its constants and, in 2-D, the section model and thickness.
struct HyperelasticModel {
  ElasticModel elastic;
  MaterialLaw law = MaterialLaw::saint_venant_kirchhoff;
};

/// validate(elastic); for neo-Hookean also ν > −1 and ν < 0.5 strictly with a message that names
/// the law (ν = 0.5 is incompressible, which a compressible law with displacement elements cannot
/// represent).
void validate(const HyperelasticModel& model, int dim, std::string_view context);

/// The state of the material at one point.
template <int D>
struct MaterialPoint {
  static constexpr int V = D == 2 ? 3 : 6;
  Eigen::Matrix<double, D, D> stress;   ///< second Piola–Kirchhoff S (in-plane part in 2-D) [Pa]
  Eigen::Matrix<double, V, V> tangent;  ///< ∂S/∂E, Voigt [Pa]
  double energy = 0.0;                  ///< W [J/m³]
  double det_f = 1.0;                   ///< J = det F (3-D, through-thickness stretch included)
};

/// Lamé constants λ, μ [Pa] of a linear material.
struct Lame {
  double lambda = 0.0, mu = 0.0;
  explicit Lame(const Material& m);
};

/// S, ℂ and W for the in-plane (2-D) or full (3-D) Green–Lagrange strain E. With J ≤ 0 (an
/// inverted point) the neo-Hookean values are undefined: det_f is returned ≤ 0 and the rest left
/// as zero; the caller reports the element.
template <int D>
MaterialPoint<D> evaluate_law(const HyperelasticModel& model, const Lame& lame,
                              const Eigen::Matrix<double, D, D>& e);

/// Strain energy density W alone (the energy-conserving scheme's discrete gradient).
template <int D>
double strain_energy_density(const HyperelasticModel& model, const Lame& lame,
                             const Eigen::Matrix<double, D, D>& e);

}  // namespace hm::fem
