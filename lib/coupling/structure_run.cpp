#include "coupling/structure_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "modal/cfpi.hpp"

namespace hm::coupling {

double LoadHistory::operator()(double t) const {
  switch (kind) {
    case Kind::constant:
      return 1.0;
    case Kind::ramp:
      return std::clamp(t / ramp_time, 0.0, 1.0);
    case Kind::harmonic:
      return std::sin(2.0 * std::numbers::pi * frequency * t + phase);
    case Kind::table: {
      const double tol = 1e-12 * std::max(1.0, std::abs(t));
      if (t < table_time.front() - tol || t > table_time.back() + tol)
        input_error("{}: the load table covers t = {} … {} s; the run needs t = {} s", table_file,
                    table_time.front(), table_time.back(), t);
      const auto hi = std::upper_bound(table_time.begin(), table_time.end(), t);
      if (hi == table_time.begin()) return table_factor.front();
      if (hi == table_time.end()) return table_factor.back();
      const auto k = static_cast<std::size_t>(hi - table_time.begin());
      const double s = (t - table_time[k - 1]) / (table_time[k] - table_time[k - 1]);
      return table_factor[k - 1] + s * (table_factor[k] - table_factor[k - 1]);
    }
  }
  return 0.0;
}

std::vector<std::string> displacement_columns(std::span<const DisplacementProbe> probes, int dim) {
  static const char* axes[] = {"ux", "uy", "uz"};
  std::vector<std::string> columns;
  for (const auto& p : probes)
    for (int a = 0; a < dim; ++a) columns.push_back(fmt::format("{}.{} [m]", p.name, axes[a]));
  return columns;
}

namespace {

/// Modal load F(t) = Σ_k g_k(t) Φᵀ f_k, from the precomputed Φᵀ f_k.
Eigen::VectorXd modal_load(std::span<const StructureLoad> loads,
                           const std::vector<Eigen::VectorXd>& projected, double t,
                           Eigen::Index modes) {
  Eigen::VectorXd F = Eigen::VectorXd::Zero(modes);
  for (std::size_t k = 0; k < loads.size(); ++k) F += loads[k].history(t) * projected[k];
  return F;
}

std::vector<double> probe_values(const modal::ModeSet& modes,
                                 std::span<const DisplacementProbe> probes,
                                 const Eigen::VectorXd& y) {
  std::vector<double> row;
  for (const auto& p : probes)
    for (int a = 0; a < modes.dim; ++a)
      row.push_back(modes.shapes.row(modes.dim * p.node + a).dot(y));
  return row;
}

}  // namespace

StructureRun run_structure(const modal::ModeSet& modes, std::span<const StructureLoad> loads,
                           std::span<const DisplacementProbe> probes, const TimeControl& time,
                           double dt, bool static_start,
                           const std::function<void(double, std::span<const double>)>& probe_row) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    input_error("structure run: time step {} s must be > 0", dt);
  if (!(time.end > 0.0)) input_error("structure run: end time {} s must be > 0", time.end);
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index m = modes.count();
  std::vector<Eigen::VectorXd> projected;
  for (const auto& load : loads) projected.push_back(modes.shapes.transpose() * load.force);

  modal::CfpiIntegrator cfpi(modes.omega.cwiseMax(0.0), modes.damping_ratio);
  Eigen::VectorXd F0 = modal_load(loads, projected, 0.0, m);
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(m);
  if (static_start)
    for (Eigen::Index i = 0; i < m; ++i)
      if (modes.omega[i] > 0.0) y0[i] = F0[i] / (modes.omega[i] * modes.omega[i]);
  cfpi.set_state(y0, Eigen::VectorXd::Zero(m), F0);

  StructureRun run;
  std::vector<Eigen::VectorXd> ys{cfpi.y()}, vs{cfpi.v()}, Fs{F0};
  run.time.push_back(0.0);
  auto record_probes = [&](double t) {
    const auto row = probe_values(modes, probes, cfpi.y());
    run.probes.time.push_back(t);
    run.probes.rows.push_back(row);
    if (probe_row) probe_row(t, row);
  };
  if (!probes.empty()) record_probes(0.0);
  OutputClock clock(0.0, time.end, time.probe_interval);  // interval 0: the end only
  const bool every_step = time.probe_interval == 0.0;
  double t = 0.0;
  while (!clock.done()) {
    // Steps of dt, the last one before each output time shortened to land on it.
    const double step = std::min(dt, clock.next() - t);
    const double t1 = clock.due(t + step) ? clock.next() : t + step;
    const Eigen::VectorXd F1 = modal_load(loads, projected, t1, m);
    cfpi.step(F0, F1, t1 - t);
    t = t1;
    F0 = F1;
    ++run.steps;
    run.time.push_back(t);
    ys.push_back(cfpi.y());
    vs.push_back(cfpi.v());
    Fs.push_back(F1);
    const bool output = clock.due(t);
    if (!probes.empty() && (output || every_step)) record_probes(t);
    if (output) clock.advance_past(t);
  }
  const auto rows = static_cast<Eigen::Index>(ys.size());
  run.y.resize(rows, m);
  run.v.resize(rows, m);
  run.F.resize(rows, m);
  for (Eigen::Index r = 0; r < rows; ++r) {
    run.y.row(r) = ys[r].transpose();
    run.v.row(r) = vs[r].transpose();
    run.F.row(r) = Fs[r].transpose();
  }
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace hm::coupling
