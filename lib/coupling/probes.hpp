#pragma once
// The probes of a run ([[probe]] of the scene): what each measures, its CSV column names, and
// one row of values from the current flow state (lib/ldd/probes.hpp does the measuring).
//   pressure  → `<name>.p [Pa]`    averaged over a sphere of `radius` around `position`
//   elevation → `<name>.eta [m]`   free-surface height (absolute) on the vertical at `position`
//   front     → `<name>.front [m]` furthest fluid point along `direction` with a height in
//                                  [band_low, band_high] (absolute heights)
//   force     → `<name>.fx [N]`, `.fy [N]` (, `.fz [N]`) pressure force on wall `wall`
//                (2-D: per metre of width, N/m)
// Missing values: a pressure probe with no fluid in its support (its weight below a tenth of a
// full lattice's: spray, or a wall sensor before the surge), a gauge with no fluid on its
// vertical and a front band with no fluid point write probe_missing_value (NaN; "nan" in the
// CSV), never 0, which would look like data. A force probe on a dry wall reads 0 N, the true
// load. A probe that never saw fluid over a run (every sample missing; a force probe: every
// sample exactly 0) is named by probes_without_fluid, warned about and recorded. Pressure probes
// and gauges can be fixed to a wall (`moves_with`): a sensor on a swaying tank moves with it.
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "ldd/flow.hpp"

namespace hm::coupling {

enum class ProbeKind { pressure, elevation, front, force };

template <int D>
struct Probe {
  std::string name;
  ProbeKind kind = ProbeKind::pressure;
  ldd::Vec<D> position = ldd::Vec<D>::Zero();    ///< pressure point / gauge position [m]
  double radius = 0.0;                           ///< pressure averaging radius [m], > 0
  int wall = -1;                                 ///< force: index into the solver's walls
  ldd::Vec<D> direction = ldd::Vec<D>::UnitX();  ///< front: unit direction
  double band_low = 0.0, band_high = 0.0;        ///< front: absolute heights [m]
  /// moves_with: index of the wall the probe is fixed to (−1: fixed in space). The position
  /// is then the host element's point `barycentric` plus `local` offset in the element's frame
  /// (tangent(s), normal), so the probe follows the wall's motion exactly when rigid.
  int attached = -1;
  ldd::Index element = -1;
  ldd::Vec<D> barycentric = ldd::Vec<D>::Zero();
  ldd::Vec<D> local = ldd::Vec<D>::Zero();
};

/// Fixes probe `probe` (its position at the wall's current placement) to wall `index`.
template <int D>
void attach_probe(Probe<D>& probe, const ldd::WallMesh<D>& wall, int index);

/// Where the probe is now [m]: its position, or the point it is fixed to on a moving wall.
template <int D>
ldd::Vec<D> probe_position(const Probe<D>& probe, std::span<const ldd::WallMesh<D>> walls);

/// CSV column names of the probes in order (without the time column).
template <int D>
std::vector<std::string> probe_columns(std::span<const Probe<D>> probes);

/// The value of a sample with no fluid in the probe's support (a quiet NaN).
inline constexpr double probe_missing_value = std::numeric_limits<double>::quiet_NaN();

/// One value per column of probe_columns, from the solver's current state; probe_missing_value
/// where a probe is dry.
template <int D>
std::vector<double> evaluate_probes(const ldd::FlowSolver<D>& solver,
                                    std::span<const Probe<D>> probes);
/// The same from `points` (a distributed flow's, gathered), the walls and the spacing dx [m].
template <int D>
std::vector<double> evaluate_probes(const ldd::PointSet<D>& points,
                                    std::span<const ldd::WallMesh<D>> walls, double dx,
                                    std::span<const Probe<D>> probes);

/// The names of the probes that saw no fluid in any of `rows` (rows of evaluate_probes, in the
/// order of `probes`): every value missing, or for a force probe every value exactly 0.
template <int D>
std::vector<std::string> probes_without_fluid(std::span<const Probe<D>> probes,
                                              std::span<const std::vector<double>> rows);

}  // namespace hm::coupling
