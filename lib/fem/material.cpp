#include "fem/material.hpp"

#include "core/errors.hpp"

namespace hm::fem {

void validate(const Material& m, std::string_view context) {
  if (!(m.youngs_modulus_pa > 0.0))
    input_error("{}: Young's modulus E = {} Pa is invalid; it must be > 0", context,
                m.youngs_modulus_pa);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5))
    input_error("{}: Poisson's ratio ν = {} is invalid; it must lie in (-1, 0.5)", context,
                m.poisson_ratio);
  if (!(m.density_kg_m3 > 0.0))
    input_error("{}: density ρ = {} kg/m³ is invalid; it must be > 0", context, m.density_kg_m3);
}

void validate(const ElasticModel& model, int dim, std::string_view context) {
  validate(model.material, context);
  if (dim == 2 && !(model.thickness_m > 0.0))
    input_error("{}: thickness = {} m is invalid; it must be > 0", context, model.thickness_m);
}

Eigen::MatrixXd elasticity_matrix(const ElasticModel& model, int dim) {
  const double e = model.material.youngs_modulus_pa;
  const double nu = model.material.poisson_ratio;
  if (dim == 3) {
    const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu));
    const double mu = e / (2 * (1 + nu));
    Eigen::MatrixXd d = Eigen::MatrixXd::Zero(6, 6);
    d.topLeftCorner(3, 3).setConstant(lambda);
    d.topLeftCorner(3, 3).diagonal().array() += 2 * mu;
    d.bottomRightCorner(3, 3).diagonal().setConstant(mu);
    return d;
  }
  HM_ASSERT(dim == 2, "dimension {} is neither 2 nor 3", dim);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(3, 3);
  if (model.plane == PlaneAssumption::plane_strain) {
    const double c = e / ((1 + nu) * (1 - 2 * nu));
    d << 1 - nu, nu, 0, nu, 1 - nu, 0, 0, 0, (1 - 2 * nu) / 2;
    return c * d;
  }
  d << 1, nu, 0, nu, 1, 0, 0, 0, (1 - nu) / 2;
  return e / (1 - nu * nu) * d;
}

}  // namespace hm::fem
