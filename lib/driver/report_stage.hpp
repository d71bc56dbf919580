#pragma once
// fsi-report: scene + results.h5 → report/ (hydromodal.report metrics.h5, metrics.json,
// metrics.md, PNG plots by gnuplot).
//
// For every probe column of the run one plot, with the reference curves the scene's
// [[report.compare]] entries give for it; a plot of the modal coordinates of a coupled or
// structure-only run; a plot of the run monitors (Δt, PPE iterations, volume drift). Per
// comparison the error metrics, over report.window (default: all) cut to where run and
// reference overlap:
//   peak error      (p_run − p_ref)/|p_ref|, p the value of largest magnitude in the window;
//   time-of-peak    t(p_run) − t(p_ref) [s];
//   RMS difference  √(mean over the reference samples of (run(t_k) − ref_k)²), run interpolated
//                   linearly, also relative to |p_ref|.
// The whole folder appears at once: it is written beside the output and renamed over it, so a
// failed report leaves the previous one (or none), never half of one.
#include <filesystem>
#include <vector>

#include "io/artefact.hpp"
#include "io/scene.hpp"

namespace hm::driver {

/// A curve t ↦ v (times ascending) [s, SI unit of the probe].
struct Curve {
  std::vector<double> t, v;
};

struct CurveMetrics {
  double peak = 0.0, peak_time = 0.0;  ///< run
  double reference_peak = 0.0, reference_peak_time = 0.0;
  double peak_error = 0.0;       ///< relative
  double peak_time_error = 0.0;  ///< [s]
  double rms = 0.0, rms_relative = 0.0;
  double window_start = 0.0, window_end = 0.0;  ///< [s]
  int samples = 0;                              ///< reference samples in the window
  /// Reference samples in the window where the run has no value (its probe was dry at a
  /// neighbouring sample: a missing value, NaN), left out of the RMS.
  int missing = 0;
  /// The run has no value at all in the window (its probe saw no fluid): the metrics are NaN.
  bool without_fluid = false;
};

/// The metrics of `run` against `reference` in [window_start, window_end] (NaN: open) cut to
/// where both curves exist. Missing run values (NaN: a dry probe) are left out: of the peak, and
/// of the RMS at the reference samples next to them (counted in `missing`); a run with no value in
/// the window gives NaN metrics and without_fluid. InputError when the window is empty or holds
/// no sample of either curve.
CurveMetrics compare_curves(const Curve& run, const Curve& reference, double window_start,
                            double window_end, const std::string& context);

/// A reference CSV: a header line, then rows of numbers; columns `time_column`, `value_column`
/// (0-based), value·scale, time·time_scale + time_offset, sorted by time (digitised curves are not
/// always in order). InputError naming the file and line on a malformed row.
Curve read_reference_csv(const std::filesystem::path& file, int time_column, int value_column,
                         double scale, double time_scale, double time_offset);

/// The probe column `column` ("tip.ux [m]") of an open results artefact; InputError naming the
/// columns it has when there is no such column.
Curve read_probe_column(const io::ArtefactReader& results, const std::string& column);

/// The reference curve of the scene's [[report.compare]] entry for `column` labelled `label`;
/// InputError listing the entries when there is none.
Curve report_reference(const io::Scene& scene, const std::string& column, const std::string& label);

/// report.window as [t0, t1] [s], NaN for an open end (no window).
std::pair<double, double> report_window_bounds(const io::Scene& scene);

void validate_report_scene(const io::Scene& scene);

/// Writes the report of `results` into the folder of `output` (output = <folder>/metrics.h5).
void run_report_stage(const io::Scene& scene, const std::filesystem::path& results,
                      const std::filesystem::path& output);

}  // namespace hm::driver
