#pragma once
// The structure alone under prescribed loads (a scene with a [structure] and no [fluid]): the
// modal equations ÿ_i + 2ζ_iω_i ẏ_i + ω_i² y_i = F_i(t) with F = Σ_k g_k(t) Φᵀ f_k — each load a
// fixed nodal force vector f_k [N] times a history g_k(t) [1] — integrated exactly by CFPI
// (LDD-SPEC §2) with the load linear inside each step. Δt is fixed (CFPI is exact for any Δt;
// the step sets how finely the histories are sampled), shortened to land on every output time.
// Displacements u = Σ Φ_i y_i (spec eq. 12, corrected) at chosen nodes are the probes.
// Units: t [s], f [N] (2-D: per structure.thickness), y [m·√kg], F [N/√kg], u [m].
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "coupling/run.hpp"
#include "modal/modes.hpp"

namespace hm::coupling {

/// g(t) of a load: constant 1; ramp min(t/T, 1); harmonic sin(2πft + φ); a CSV table
/// (`t [s]`, `factor [1]`), linear between rows (the CFPI load model), outside it an InputError.
struct LoadHistory {
  enum class Kind { constant, ramp, harmonic, table };
  Kind kind = Kind::constant;
  double ramp_time = 0.0;  ///< [s], > 0 for a ramp
  double frequency = 0.0;  ///< [Hz]
  double phase = 0.0;      ///< [rad]
  std::vector<double> table_time, table_factor;
  std::string table_file;  ///< for messages
  double operator()(double t) const;
};

struct StructureLoad {
  std::string name;
  Eigen::VectorXd force;  ///< full nodal force vector f [N] (n_nodes·dim), g = 1
  LoadHistory history;
};

/// A displacement probe: the node nearest to the requested point.
struct DisplacementProbe {
  std::string name;
  Eigen::Index node = 0;
};

/// CSV column names: `<name>.ux [m]`, `.uy [m]` (, `.uz [m]`) per probe.
std::vector<std::string> displacement_columns(std::span<const DisplacementProbe> probes, int dim);

struct StructureRun {
  ProbeSeries probes;         ///< one row per probe time
  std::vector<double> time;   ///< [s], the start and every step end
  Eigen::MatrixXd y, v, F;    ///< n_times × n_modes: modal coordinates, velocities, forces
  double wall_seconds = 0.0;  ///< [s]
  long steps = 0;
};

/// Integrates `modes` from rest at t = 0 (or from the static solution y = F(0)/ω² when
/// `static_start`) to time.end with steps of `dt` [s] under `loads`; `probe_row`, if set, gets
/// every probe row as it is made. InputError for dt ≤ 0 or a load history outside its table.
StructureRun run_structure(const modal::ModeSet& modes, std::span<const StructureLoad> loads,
                           std::span<const DisplacementProbe> probes, const TimeControl& time,
                           double dt, bool static_start,
                           const std::function<void(double, std::span<const double>)>& probe_row);

}  // namespace hm::coupling
