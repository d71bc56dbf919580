#pragma once
// A body in free rigid motion, optionally flexible (issue 7: the wedge in free fall).
//
// A free-free mode set (no clamped group) holds the body's rigid-body modes (ω ≈ 0: the
// translations and the rotations, linearised) beside its elastic ones; the elastic modes carry
// no momentum (Γ = ΦᵀM T = 0, they are M-orthogonal to the translations). A body guided along one
// axis — the vertical drop of a wedge on its rig — keeps the elastic modes and replaces the rigid
// ones by the one translation it is free in, as a mode with ω = 0 mass-normalised for the body's
// mass M: Φ = e/√M at every vertex, Γ = √M·e. CFPI integrates ω = 0 exactly (a double
// integration of the load), the body's weight enters through Γ·g (FlexibleBody::inertial_force),
// the fluid's force through Φᵀf = e·f_total/√M, and the strong coupling's added-mass matrix holds
// the fluid's added mass of the translation (it grows by orders of magnitude at a slamming
// impact, which a staggered scheme does not survive).
// Units as in flexible_body.hpp; the translation's coordinate y = √M·X [m·√kg].
#include <string>

#include "coupling/flexible_body.hpp"

namespace hm::coupling {

/// What make_free_translation did.
struct FreeTranslation {
  int axis = 0;                    ///< the free direction e = e_axis
  double mass = 0.0;               ///< M [kg] (2-D: for the structure's thickness)
  Eigen::Index mode = 0;           ///< index of the translation among the body's modes
  Eigen::Index rigid_dropped = 0;  ///< rigid-body modes removed
};

/// Replaces the rigid-body modes of `modes` (|ω| ≤ 1e-4·max|ω|) by the translation along `axis`
/// (appended last) and sets its initial velocity `velocity` [m/s] along e (the elastic modes
/// start at rest). InputError (naming `context`) when the set has no rigid-body modes (a clamped
/// structure cannot move freely), carries no mass along the axis, has no participation factors,
/// or an elastic mode carries momentum along it (the set is not free-free).
template <int D>
FreeTranslation make_free_translation(ModalSurface<D>& modes, int axis, double velocity,
                                      const std::string& context);

}  // namespace hm::coupling
