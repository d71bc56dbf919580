#include "coupling/free_motion.hpp"

#include <cmath>
#include <vector>

#include "core/errors.hpp"

namespace hm::coupling {

namespace {

constexpr double kRigidFrequency = 1e-4;   ///< |ω| below this·max|ω|: a rigid-body mode
constexpr double kElasticMomentum = 1e-6;  ///< |Γ_elastic,axis| above this·√M: not free-free

}  // namespace

template <int D>
FreeTranslation make_free_translation(ModalSurface<D>& modes, int axis, double velocity,
                                      const std::string& context) {
  const Eigen::Index m = modes.modes();
  if (axis < 0 || axis >= D) input_error("{}: free axis {} of a {}-D body", context, axis, D);
  if (modes.participation.rows() != m || modes.participation.cols() != D)
    input_error(
        "{}: the mode set has no participation factors; a free body needs them for its "
        "mass",
        context);
  const double largest = modes.omega.cwiseAbs().maxCoeff();
  std::vector<Eigen::Index> elastic, rigid;
  for (Eigen::Index i = 0; i < m; ++i)
    (std::abs(modes.omega[i]) <= kRigidFrequency * largest ? rigid : elastic).push_back(i);
  if (rigid.empty())
    input_error(
        "{}: the mode set has no rigid-body modes (|ω| ≤ {}·max|ω|): a body in free "
        "motion needs a free-free mode set (structure.clamped = \"\")",
        context, kRigidFrequency);
  double mass = 0.0;
  for (const Eigen::Index i : rigid)
    mass += modes.participation(i, axis) * modes.participation(i, axis);
  if (!(mass > 0.0))
    input_error("{}: the rigid-body modes carry no mass along axis {}", context, axis);
  const double root = std::sqrt(mass);
  for (const Eigen::Index i : elastic)
    if (std::abs(modes.participation(i, axis)) > kElasticMomentum * root)
      input_error(
          "{}: elastic mode {} ({:.4g} rad/s) carries momentum along axis {} (Γ = {:.3g} "
          "√kg against √M = {:.3g}): the mode set is not free-free; request more modes "
          "so that all rigid-body modes are in the set",
          context, i, modes.omega[i], axis, modes.participation(i, axis), root);

  const auto e = static_cast<Eigen::Index>(elastic.size());
  const auto rows = modes.shapes.rows();
  ModalSurface<D> out;
  out.x0 = modes.x0;
  out.shapes.resize(rows, e + 1);
  out.omega.resize(e + 1);
  out.zeta.resize(e + 1);
  out.participation = Eigen::MatrixXd::Zero(e + 1, D);
  for (Eigen::Index k = 0; k < e; ++k) {
    const Eigen::Index i = elastic[static_cast<std::size_t>(k)];
    out.shapes.col(k) = modes.shapes.col(i);
    out.omega[k] = modes.omega[i];
    out.zeta[k] = modes.zeta[i];
    out.participation.row(k) = modes.participation.row(i);
  }
  out.shapes.col(e).setZero();
  for (Eigen::Index r = axis; r < rows; r += D) out.shapes(r, e) = 1.0 / root;
  out.omega[e] = 0.0;
  out.zeta[e] = 0.0;
  out.participation(e, axis) = root;
  out.initial_velocity = Eigen::VectorXd::Zero(e + 1);
  out.initial_velocity[e] = root * velocity;
  modes = std::move(out);
  return {axis, mass, e, static_cast<Eigen::Index>(rigid.size())};
}

template FreeTranslation make_free_translation<2>(ModalSurface<2>&, int, double,
                                                  const std::string&);
template FreeTranslation make_free_translation<3>(ModalSurface<3>&, int, double,
                                                  const std::string&);

}  // namespace hm::coupling
