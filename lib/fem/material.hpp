#pragma once
// Linear isotropic elastic material and the 2-D modelling assumption of the structure.
// Units: Pa, kg/m³, m.
#include <string_view>

#include <Eigen/Core>

namespace hm::fem {

struct Material {
  double youngs_modulus_pa = 0.0;  ///< E [Pa], > 0
  double poisson_ratio = 0.0;      ///< ν [-], −1 < ν < 0.5 (0.5 would be incompressible)
  double density_kg_m3 = 0.0;      ///< ρ [kg/m³], > 0
};

/// Throws InputError naming `context` (e.g. the scene key "structure.material"), the quantity,
/// its value and the accepted range, for the first property out of range.
void validate(const Material& material, std::string_view context);

/// How a 2-D (x, y) section stands for the 3-D body.
enum class PlaneAssumption {
  plane_strain,  ///< ε_zz = 0: a long prism (a gate spanning a channel)
  plane_stress,  ///< σ_zz = 0: a thin plate loaded in its plane
};

/// What the element matrices need: the material and, in 2-D, the section model and thickness.
/// 2-D stiffness and mass are the per-unit-thickness matrices times `thickness_m`.
struct ElasticModel {
  Material material;
  PlaneAssumption plane = PlaneAssumption::plane_strain;  ///< 2-D only
  double thickness_m = 1.0;                               ///< 2-D only, [m], > 0
};

/// validate(material) plus the thickness (2-D).
void validate(const ElasticModel& model, int dim, std::string_view context);

/// Voigt elasticity matrix D [Pa]: σ = D ε with engineering shear strains.
/// 3-D: 6×6, ε = (εxx, εyy, εzz, γyz, γxz, γxy). 2-D: 3×3, ε = (εxx, εyy, γxy).
Eigen::MatrixXd elasticity_matrix(const ElasticModel& model, int dim);

}  // namespace hm::fem
