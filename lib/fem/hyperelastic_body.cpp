#include "fem/hyperelastic_body.hpp"

#include <algorithm>
#include <cstdint>
#include <limits>

#include <Eigen/LU>

#include "core/errors.hpp"
#include "fem/elements.hpp"
#include "fem/quadrature.hpp"

namespace hm::fem {
namespace {

using mesh::Index;

template <int D>
struct Sizes {
  static constexpr int nodes = D == 2 ? 6 : 10;
  static constexpr int voigt = D == 2 ? 3 : 6;
  static constexpr int dofs = nodes * D;
  using Grad = Eigen::Matrix<double, nodes, D>;
  using Tensor = Eigen::Matrix<double, D, D>;
  using Voigt = Eigen::Matrix<double, voigt, 1>;
  using VoigtMatrix = Eigen::Matrix<double, voigt, voigt>;
  using Local = Eigen::Matrix<double, dofs, 1>;
  using LocalMatrix = Eigen::Matrix<double, dofs, dofs>;
  using Strain = Eigen::Matrix<double, voigt, dofs>;
};

/// Index pairs (I, J) of the Voigt components, in the order of material.hpp.
template <int D>
constexpr std::array<std::array<int, 2>, Sizes<D>::voigt> voigt_pairs() {
  if constexpr (D == 2)
    return {{{0, 0}, {1, 1}, {0, 1}}};
  else
    return {{{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}}};
}

/// Engineering-strain Voigt vector of sym(X): diagonal X_II, off-diagonal X_IJ + X_JI.
template <int D>
typename Sizes<D>::Voigt strain_voigt(const typename Sizes<D>::Tensor& x) {
  typename Sizes<D>::Voigt v;
  const auto pairs = voigt_pairs<D>();
  for (int k = 0; k < Sizes<D>::voigt; ++k) {
    const auto [i, j] = pairs[k];
    v(k) = i == j ? x(i, i) : x(i, j) + x(j, i);
  }
  return v;
}

/// Stress Voigt vector of a symmetric tensor.
template <int D>
typename Sizes<D>::Voigt stress_voigt(const typename Sizes<D>::Tensor& s) {
  typename Sizes<D>::Voigt v;
  const auto pairs = voigt_pairs<D>();
  for (int k = 0; k < Sizes<D>::voigt; ++k) v(k) = s(pairs[k][0], pairs[k][1]);
  return v;
}

/// B(F): δE (engineering Voigt) = B δu for δu of the element's nodes, δE = sym(Fᵀ ∇δu).
template <int D>
typename Sizes<D>::Strain strain_operator(const typename Sizes<D>::Tensor& f,
                                          const typename Sizes<D>::Grad& g) {
  typename Sizes<D>::Strain b;
  const auto pairs = voigt_pairs<D>();
  for (int a = 0; a < Sizes<D>::nodes; ++a)
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < Sizes<D>::voigt; ++k) {
        const auto [p, q] = pairs[k];
        b(k, D * a + i) = p == q ? f(i, p) * g(a, p) : f(i, p) * g(a, q) + f(i, q) * g(a, p);
      }
  return b;
}

/// The geometric stiffness ∫ ∇N_a·S∇N_b δ_ij of one point, added to k with weight w.
template <int D>
void add_geometric(const typename Sizes<D>::Grad& g, const typename Sizes<D>::Tensor& s, double w,
                   typename Sizes<D>::LocalMatrix& k) {
  const Eigen::Matrix<double, Sizes<D>::nodes, Sizes<D>::nodes> h = g * s * g.transpose();
  for (int a = 0; a < Sizes<D>::nodes; ++a)
    for (int b = 0; b < Sizes<D>::nodes; ++b)
      for (int i = 0; i < D; ++i) k(D * a + i, D * b + i) += w * h(a, b);
}

template <int D>
typename Sizes<D>::Local local_vector(const mesh::StructureMesh& mesh, Index cell,
                                      const Eigen::VectorXd& global) {
  typename Sizes<D>::Local local;
  for (int a = 0; a < Sizes<D>::nodes; ++a)
    local.template segment<D>(D * a) = global.segment<D>(D * mesh.cells(cell, a));
  return local;
}

/// F = I + ∇u at one point from the element's nodal displacements.
template <int D>
typename Sizes<D>::Tensor deformation_gradient(const typename Sizes<D>::Local& u,
                                               const typename Sizes<D>::Grad& g) {
  const Eigen::Map<const Eigen::Matrix<double, Sizes<D>::nodes, D, Eigen::RowMajor>> nodal(
      u.data());
  return Sizes<D>::Tensor::Identity() + nodal.transpose() * g;
}

template <int D>
typename Sizes<D>::Tensor displacement_gradient(const typename Sizes<D>::Local& u,
                                                const typename Sizes<D>::Grad& g) {
  const Eigen::Map<const Eigen::Matrix<double, Sizes<D>::nodes, D, Eigen::RowMajor>> nodal(
      u.data());
  return nodal.transpose() * g;
}

/// E = sym H + ½HᵀH, H = ∇u: accurate to round-off relative to E itself.
template <int D>
typename Sizes<D>::Tensor green_lagrange(const typename Sizes<D>::Local& u,
                                         const typename Sizes<D>::Grad& g) {
  const typename Sizes<D>::Tensor h = displacement_gradient<D>(u, g);
  return 0.5 * (h + h.transpose() + h.transpose() * h);
}

const QuadratureRule& rule(int dim, int degree) {
  return dim == 2 ? triangle_rule(degree) : tetrahedron_rule(degree);
}

ShapeValues shape(int dim, const Eigen::Vector3d& xi) {
  return dim == 2 ? tri6_shape(xi) : tet10_shape(xi);
}

/// What one cell contributes.
template <int D>
struct CellResult {
  typename Sizes<D>::Local force = Sizes<D>::Local::Zero();
  typename Sizes<D>::LocalMatrix tangent = Sizes<D>::LocalMatrix::Zero();
  double energy = 0.0, power = 0.0;
  double min_det_f = std::numeric_limits<double>::infinity();
};

}  // namespace

HyperelasticBody::HyperelasticBody(mesh::StructureMesh mesh, const HyperelasticModel& model,
                                   std::string_view context)
    : mesh_(std::move(mesh)),
      model_(model),
      lame_((validate(model, mesh_.dim, context), model.elastic.material)),
      pattern_((validate_mesh(mesh_, context), mesh_)),
      colours_(colour_cells(mesh_)) {
  const int dim = mesh_.dim;
  const double thickness = dim == 2 ? model_.elastic.thickness_m : 1.0;
  tangent0_ = elasticity_matrix(model_.elastic, dim);
  const QuadratureRule& q = rule(dim, 2);
  quadrature_.resize(static_cast<std::size_t>(mesh_.cells.rows()));
  std::vector<double> k(pattern_.nonzeros(), 0.0);
  mass_values_.assign(pattern_.nonzeros(), 0.0);
  Index inverted = -1;
  for (const std::vector<Index>& cells : colours_) {
    const auto count = static_cast<std::int64_t>(cells.size());
#pragma omp parallel for schedule(dynamic, 64)
    for (std::int64_t c = 0; c < count; ++c) {
      const Index cell = cells[static_cast<std::size_t>(c)];
      const Eigen::MatrixXd coords = cell_coordinates(mesh_, cell);
      const ElementMatrices e =
          element_matrices(coords, tangent0_, model_.elastic.material.density_kg_m3, thickness);
      if (!(e.min_jacobian > 0.0)) {
#pragma omp critical(hm_fem_inverted)
        inverted = std::max(inverted, cell);
      }
      auto& points = quadrature_[static_cast<std::size_t>(cell)];
      for (std::size_t p = 0; p < q.points.size(); ++p) {
        const ShapeValues s = shape(dim, q.points[p]);
        const Eigen::MatrixXd jac = coords.transpose() * s.dn;
        points.push_back({s.dn * jac.inverse(), q.weights[p] * jac.determinant() * thickness});
      }
      scatter(pattern_, mesh_, cell, e.stiffness, k);
      scatter(pattern_, mesh_, cell, e.mass, mass_values_);
    }
  }
  if (inverted >= 0)
    input_error("{}: cell {} is inverted or degenerate (Jacobian determinant ≤ 0)", context,
                inverted);
  stiffness_ = pattern_.matrix(k);
  mass_ = pattern_.matrix(mass_values_);
}

template <int D>
BodyEvaluation HyperelasticBody::evaluate_dim(const Eigen::VectorXd& u,
                                              const EvaluationRequest& request) const {
  using S = Sizes<D>;
  HM_ASSERT(u.size() == dof_count(), "displacement has {} entries for {} DOFs", u.size(),
            dof_count());
  const bool damped = request.velocity != nullptr && request.beta > 0.0;
  const bool conserving = request.start != nullptr;
  const typename S::VoigtMatrix c0 = tangent0_;
  BodyEvaluation out;
  out.force = Eigen::VectorXd::Zero(dof_count());
  out.symmetric = !conserving;
  std::vector<double> k(request.tangent ? pattern_.nonzeros() : 0, 0.0);
  const auto cells = mesh_.cells.rows();
  std::vector<double> energy(static_cast<std::size_t>(cells)), power(energy.size()),
      det(energy.size());

  auto cell_result = [&](Index cell) {
    CellResult<D> r;
    const typename S::Local ue = local_vector<D>(mesh_, cell, u);
    typename S::Local u0e, ve;
    if (conserving) u0e = local_vector<D>(mesh_, cell, *request.start);
    if (damped) ve = local_vector<D>(mesh_, cell, *request.velocity);
    for (const QuadraturePoint& point : quadrature_[static_cast<std::size_t>(cell)]) {
      const typename S::Grad g = point.grad;
      const double w = point.weight;
      const typename S::Tensor f = deformation_gradient<D>(ue, g);
      const typename S::Tensor e = green_lagrange<D>(ue, g);
      const MaterialPoint<D> at_u = evaluate_law<D>(model_, lame_, e);
      r.min_det_f = std::min(r.min_det_f, at_u.det_f);
      if (!(at_u.det_f > 0.0)) continue;
      r.energy += w * at_u.energy;
      // The force's stress and the F of its strain operator: at u, or the discrete gradient.
      typename S::Tensor stress = at_u.stress, f_force = f;
      const typename S::Strain b = strain_operator<D>(f, g);
      if (conserving) {
        const typename S::Tensor f0 = deformation_gradient<D>(u0e, g);
        const typename S::Tensor e_start = green_lagrange<D>(u0e, g);
        const MaterialPoint<D> mid = evaluate_law<D>(model_, lame_, 0.5 * (e + e_start));
        const typename S::Tensor de = e - e_start;
        stress = mid.stress;
        const double de2 = de.squaredNorm();
        if (de2 > 1e-28) {
          const double w0 = strain_energy_density<D>(model_, lame_, e_start);
          stress += (at_u.energy - w0 - mid.stress.cwiseProduct(de).sum()) / de2 * de;
        }
        f_force = 0.5 * (f0 + f);
        const typename S::Strain bm = strain_operator<D>(f_force, g);
        r.force.noalias() += w * bm.transpose() * stress_voigt<D>(stress);
        if (request.tangent) {
          r.tangent.noalias() +=
              (0.5 * w * request.stiffness_weight) * bm.transpose() * mid.tangent * b;
          add_geometric<D>(g, stress, 0.5 * w * request.stiffness_weight, r.tangent);
        }
      } else {
        r.force.noalias() += w * b.transpose() * stress_voigt<D>(stress);
        if (request.tangent) {
          r.tangent.noalias() += (w * request.stiffness_weight) * b.transpose() * at_u.tangent * b;
          add_geometric<D>(g, stress, w * request.stiffness_weight, r.tangent);
        }
      }
      if (damped) {
        const typename S::Strain bd = strain_operator<D>(f_force, g);
        const typename S::Local fd = (request.beta * w) * bd.transpose() * (c0 * (bd * ve));
        r.force += fd;
        r.power += ve.dot(fd);
        if (request.tangent)
          r.tangent.noalias() +=
              (request.beta * w * request.damping_weight) * bd.transpose() * c0 * bd;
      }
    }
    return r;
  };

  for (const std::vector<Index>& colour : colours_) {
    const auto count = static_cast<std::int64_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 32)
    for (std::int64_t i = 0; i < count; ++i) {
      const Index cell = colour[static_cast<std::size_t>(i)];
      const CellResult<D> r = cell_result(cell);
      const auto slot = static_cast<std::size_t>(cell);
      energy[slot] = r.energy;
      power[slot] = r.power;
      det[slot] = r.min_det_f;
      for (int a = 0; a < S::nodes; ++a)
        out.force.segment<D>(D * mesh_.cells(cell, a)) += r.force.template segment<D>(D * a);
      if (request.tangent) scatter(pattern_, mesh_, cell, Eigen::MatrixXd(r.tangent), k);
    }
  }
  for (Index cell = 0; cell < cells; ++cell) {
    const auto slot = static_cast<std::size_t>(cell);
    out.strain_energy += energy[slot];
    out.damping_power += power[slot];
    if (out.worst_cell < 0 || det[slot] < out.min_det_f) {
      out.min_det_f = det[slot];
      out.worst_cell = cell;
    }
  }
  if (request.tangent) {
    if (request.mass_weight != 0.0)
      for (std::size_t n = 0; n < k.size(); ++n) k[n] += request.mass_weight * mass_values_[n];
    out.tangent = pattern_.matrix(k);
  }
  return out;
}

BodyEvaluation HyperelasticBody::evaluate(const Eigen::VectorXd& u,
                                          const EvaluationRequest& request) const {
  return dim() == 2 ? evaluate_dim<2>(u, request) : evaluate_dim<3>(u, request);
}

double HyperelasticBody::strain_energy(const Eigen::VectorXd& u) const {
  return evaluate(u).strain_energy;
}

template <int D>
Eigen::VectorXd HyperelasticBody::second_derivative_dim(const Eigen::VectorXd& a,
                                                        const Eigen::VectorXd& b) const {
  using S = Sizes<D>;
  const typename S::VoigtMatrix c0 = tangent0_;
  const typename S::Tensor identity = S::Tensor::Identity();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dof_count());
  for (const std::vector<Index>& colour : colours_) {
    const auto count = static_cast<std::int64_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 32)
    for (std::int64_t i = 0; i < count; ++i) {
      const Index cell = colour[static_cast<std::size_t>(i)];
      const typename S::Local ae = local_vector<D>(mesh_, cell, a);
      const typename S::Local be = local_vector<D>(mesh_, cell, b);
      typename S::Local fe = S::Local::Zero();
      for (const QuadraturePoint& point : quadrature_[static_cast<std::size_t>(cell)]) {
        const typename S::Grad g = point.grad;
        const typename S::Tensor ga = displacement_gradient<D>(ae, g);
        const typename S::Tensor gb = displacement_gradient<D>(be, g);
        // d²f[a,b]·w = ∫ L(w):ℂ:q(a,b) + q(w,b):ℂ:L(a) + q(w,a):ℂ:L(b), with L(x) = sym ∇x,
        // q(x,y) = sym(∇xᵀ∇y) and q(w,y) = B(∇y) w.
        const typename S::Voigt q_ab =
            strain_voigt<D>(0.5 * (ga.transpose() * gb + gb.transpose() * ga));
        fe.noalias() +=
            point.weight * (strain_operator<D>(identity, g).transpose() * (c0 * q_ab) +
                            strain_operator<D>(gb, g).transpose() * (c0 * strain_voigt<D>(ga)) +
                            strain_operator<D>(ga, g).transpose() * (c0 * strain_voigt<D>(gb)));
      }
      for (int n = 0; n < S::nodes; ++n)
        out.segment<D>(D * mesh_.cells(cell, n)) += fe.template segment<D>(D * n);
    }
  }
  return out;
}

template <int D>
Eigen::MatrixXd HyperelasticBody::second_derivatives_dim(const Eigen::MatrixXd& directions) const {
  using S = Sizes<D>;
  const typename S::VoigtMatrix c0 = tangent0_;
  const typename S::Tensor identity = S::Tensor::Identity();
  const auto k = static_cast<int>(directions.cols());
  const int pairs = k * (k + 1) / 2;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(dof_count(), pairs);
  for (const std::vector<Index>& colour : colours_) {
    const auto count = static_cast<std::int64_t>(colour.size());
#pragma omp parallel for schedule(dynamic, 32)
    for (std::int64_t c = 0; c < count; ++c) {
      const Index cell = colour[static_cast<std::size_t>(c)];
      std::vector<typename S::Local> local(static_cast<std::size_t>(k));
      for (int i = 0; i < k; ++i)
        for (int a = 0; a < S::nodes; ++a)
          local[static_cast<std::size_t>(i)].template segment<D>(D * a) =
              directions.col(i).template segment<D>(D * mesh_.cells(cell, a));
      Eigen::Matrix<double, S::dofs, Eigen::Dynamic> fe =
          Eigen::Matrix<double, S::dofs, Eigen::Dynamic>::Zero(S::dofs, pairs);
      std::vector<typename S::Tensor> grad(static_cast<std::size_t>(k));
      std::vector<typename S::Strain> b_nonlinear(static_cast<std::size_t>(k));
      std::vector<typename S::Voigt> stress(static_cast<std::size_t>(k));
      for (const QuadraturePoint& point : quadrature_[static_cast<std::size_t>(cell)]) {
        const typename S::Grad g = point.grad;
        const typename S::Strain b_linear = strain_operator<D>(identity, g);
        for (std::size_t i = 0; i < grad.size(); ++i) {
          grad[i] = displacement_gradient<D>(local[i], g);
          b_nonlinear[i] = strain_operator<D>(grad[i], g);
          stress[i] = c0 * strain_voigt<D>(grad[i]);  // ℂ:L(a_i)
        }
        // The terms of second_derivative_dim, pair by pair.
        int column = 0;
        for (std::size_t i = 0; i < grad.size(); ++i)
          for (std::size_t j = i; j < grad.size(); ++j, ++column) {
            const typename S::Voigt q_ij = strain_voigt<D>(
                0.5 * (grad[i].transpose() * grad[j] + grad[j].transpose() * grad[i]));
            fe.col(column).noalias() += point.weight * (b_linear.transpose() * (c0 * q_ij) +
                                                        b_nonlinear[j].transpose() * stress[i] +
                                                        b_nonlinear[i].transpose() * stress[j]);
          }
      }
      for (int n = 0; n < S::nodes; ++n)
        out.middleRows<D>(D * mesh_.cells(cell, n)) += fe.template middleRows<D>(D * n);
    }
  }
  return out;
}

Eigen::MatrixXd HyperelasticBody::second_derivatives(const Eigen::MatrixXd& directions) const {
  HM_ASSERT(directions.rows() == dof_count(), "{} rows for {} DOFs", directions.rows(),
            dof_count());
  return dim() == 2 ? second_derivatives_dim<2>(directions) : second_derivatives_dim<3>(directions);
}

Eigen::VectorXd HyperelasticBody::second_derivative(const Eigen::VectorXd& a,
                                                    const Eigen::VectorXd& b) const {
  return dim() == 2 ? second_derivative_dim<2>(a, b) : second_derivative_dim<3>(a, b);
}

Eigen::VectorXd HyperelasticBody::body_force(const Eigen::VectorXd& g) const {
  HM_ASSERT(g.size() == dim(), "acceleration has {} components in {}-D", g.size(), dim());
  Eigen::VectorXd uniform(dof_count());
  for (Index n = 0; n < mesh_.node_count(); ++n) uniform.segment(dim() * n, dim()) = g;
  return mass_ * uniform;
}

}  // namespace hm::fem
