#include "driver/report_stage.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <numeric>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/text.hpp"
#include "driver/gnuplot.hpp"
#include "driver/metrics_json.hpp"
#include "io/artefact.hpp"
#include "io/schema.hpp"

namespace hm::driver {
namespace {

constexpr const char* stage_name = "fsi-report";
namespace ds = io::ds;
namespace ra = io::results_attr;

/// c at t, linear between samples, clamped at the ends; NaN where a sample it uses is missing.
double interpolate(const Curve& c, double t) {
  const auto it = std::lower_bound(c.t.begin(), c.t.end(), t);
  if (it == c.t.begin()) return c.v.front();
  if (it == c.t.end()) return c.v.back();
  const auto k = static_cast<std::size_t>(it - c.t.begin());
  if (*it == t) return c.v[k];
  const double w = (t - c.t[k - 1]) / (c.t[k] - c.t[k - 1]);
  return (1 - w) * c.v[k - 1] + w * c.v[k];
}

/// The sample of largest magnitude in [a, b], missing values left out: (value, time); the time
/// is NaN when there is no sample.
std::pair<double, double> peak_in(const Curve& c, double a, double b) {
  std::pair<double, double> best{0.0, std::numeric_limits<double>::quiet_NaN()};
  for (std::size_t k = 0; k < c.t.size(); ++k)
    if (c.t[k] >= a && c.t[k] <= b && !std::isnan(c.v[k]) &&
        (std::isnan(best.second) || std::abs(c.v[k]) > std::abs(best.first)))
      best = {c.v[k], c.t[k]};
  return best;
}

/// One [[report.compare]] entry resolved.
struct Comparison {
  std::string column, label;
  std::filesystem::path file;
  Curve reference;
};

struct RunData {
  std::vector<std::string> columns;
  std::vector<Curve> probes;  ///< per column
  Curve dt, ppe_iterations, volume_drift;
  std::vector<double> modal_time;
  io::MatrixRM modal;  ///< n_rows × n_modes (empty: no structure)
  /// A coupled run's structure monitors (empty when the run did not record them).
  std::vector<double> monitor_time;
  io::MatrixRM structure_energy;  ///< n_steps × 5 [J]: kinetic, strain, work, damping, numerical
  Curve structure_stretch, coupling_iterations, structure_solver_iterations;
};

/// The probe columns of a results artefact (none when it has no probes).
void read_probes(const io::ArtefactReader& r, RunData& d) {
  if (!r.has(ds::probe_time)) return;
  d.columns = split_csv_fields(r.string_attribute(ra::probe_columns).value_or(""));
  const std::vector<double> t = r.read_values(ds::probe_time);
  const io::MatrixRM values = r.read_matrix(ds::probe_values);
  for (Eigen::Index c = 0; c < values.cols(); ++c) {
    Curve curve;
    curve.t = t;
    for (Eigen::Index k = 0; k < values.rows(); ++k) curve.v.push_back(values(k, c));
    d.probes.push_back(std::move(curve));
  }
  if (d.columns.size() != d.probes.size())
    input_error("{}: {} probe column names for {} columns", r.path().string(), d.columns.size(),
                d.probes.size());
}

RunData read_run(const std::filesystem::path& results) {
  const io::ArtefactReader r(results, io::results_schema());
  RunData d;
  read_probes(r, d);
  if (r.has(ds::monitor_time)) {
    const std::vector<double> t = r.read_values(ds::monitor_time);
    d.dt = {t, r.read_values(ds::monitor_dt)};
    d.ppe_iterations = {t, r.read_values(ds::monitor_ppe_iterations)};
    d.volume_drift = {t, r.read_values(ds::monitor_volume_drift)};
    d.monitor_time = t;
    if (r.has(ds::monitor_structure_energy))
      d.structure_energy = r.read_matrix(ds::monitor_structure_energy);
    if (r.has(ds::monitor_structure_stretch))
      d.structure_stretch = {t, r.read_values(ds::monitor_structure_stretch)};
    if (r.has(ds::monitor_coupling_iterations))
      d.coupling_iterations = {t, r.read_values(ds::monitor_coupling_iterations)};
    if (r.has(ds::monitor_structure_solver_iterations))
      d.structure_solver_iterations = {t, r.read_values(ds::monitor_structure_solver_iterations)};
  }
  if (r.has(ds::modal_time)) {
    d.modal_time = r.read_values(ds::modal_time);
    d.modal = r.read_matrix(ds::modal_coordinates);
  }
  return d;
}

/// report.window, empty without a [report] section (a scene without references still gets its
/// plots).
Eigen::VectorXd report_window(const io::Scene& scene) {
  return scene.has("report") ? scene.vector("report.window") : Eigen::VectorXd();
}

/// The [[report.compare]] entries (none without a [report] section).
std::vector<io::SceneView> compare_entries(const io::Scene& scene) {
  return scene.has("report") ? scene.array("report.compare") : std::vector<io::SceneView>{};
}

std::vector<Comparison> comparisons(const io::Scene& scene, const RunData& run) {
  std::vector<Comparison> out;
  for (const io::SceneView& view : compare_entries(scene)) {
    Comparison c;
    c.column = view.string("column");
    if (std::find(run.columns.begin(), run.columns.end(), c.column) == run.columns.end())
      input_error("{} = \"{}\": no such probe column in the run (columns: {})",
                  view.where("column"), c.column, join(run.columns, ", "));
    c.file = view.file_path("file");
    c.label = view.string("label").empty() ? c.file.stem().string() : view.string("label");
    c.reference =
        read_reference_csv(c.file, static_cast<int>(view.integer("time_column")),
                           static_cast<int>(view.integer("value_column")), view.number("scale"),
                           view.number("time_scale"), view.number("time_offset"));
    out.push_back(std::move(c));
  }
  return out;
}

std::string metrics_markdown(const std::vector<Comparison>& cs,
                             const std::vector<CurveMetrics>& ms) {
  std::string md =
      "| probe | reference | peak | reference peak | peak error | at | reference at | Δt of peak "
      "| RMS | RMS / \\|ref. peak\\| | window |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const auto& m = ms[k];
    md += fmt::format(
        "| `{}` | {} | {:.4g} | {:.4g} | {:+.1f} % | {:.4g} s | {:.4g} s | {:+.4f} s | {:.3g} | "
        "{:.1f} % | {:.3g}–{:.3g} s |\n",
        cs[k].column, cs[k].label, m.peak, m.reference_peak, 100 * m.peak_error, m.peak_time,
        m.reference_peak_time, m.peak_time_error, m.rms, 100 * m.rms_relative, m.window_start,
        m.window_end);
  }
  for (std::size_t k = 0; k < cs.size(); ++k) {
    if (ms[k].without_fluid)
      md += fmt::format("\n`{}` saw no fluid in the window: no metrics against {}.\n", cs[k].column,
                        cs[k].label);
    else if (ms[k].missing > 0)
      md += fmt::format(
          "\n`{}` had no fluid at {} of the {} reference samples (missing values, left out of "
          "the RMS).\n",
          cs[k].column, ms[k].missing, ms[k].samples);
  }
  return md;
}

nlohmann::ordered_json metrics_json(const std::vector<Comparison>& cs,
                                    const std::vector<CurveMetrics>& ms) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < cs.size(); ++k) {
    nlohmann::ordered_json entry = {{"column", cs[k].column},
                                    {"reference", cs[k].label},
                                    {"reference_file", cs[k].file.string()}};
    entry.update(curve_metrics_json(ms[k]));
    j.push_back(std::move(entry));
  }
  return j;
}

/// structure_monitors.png: what a coupled run recorded of its structure — the energy balance
/// (kinetic, strain, the fluid's and gravity's work, structural damping, numerical dissipation),
/// the stretch, and the PPE solves and structure Newton iterations of each step.
std::string structure_monitor_script(const std::filesystem::path& folder, const RunData& run) {
  std::vector<std::string> panels;
  if (run.structure_energy.rows() > 0) {
    std::ofstream out(folder / "data" / "structure_energy.dat");
    out.precision(17);
    for (Eigen::Index k = 0; k < run.structure_energy.rows(); ++k) {
      out << run.monitor_time[static_cast<std::size_t>(k)];
      for (Eigen::Index c = 0; c < run.structure_energy.cols(); ++c)
        out << ' ' << run.structure_energy(k, c);
      out << '\n';
    }
    const char* names[] = {"kinetic", "strain", "work of the loads", "structural damping",
                           "numerical dissipation"};
    std::vector<std::string> series;
    for (Eigen::Index c = 0; c < std::min<Eigen::Index>(run.structure_energy.cols(), 5); ++c)
      series.push_back(fmt::format("'data/structure_energy.dat' using 1:{} with lines title '{}'",
                                   c + 2, names[c]));
    panels.push_back("set key top left\nset ylabel 'structure energy [J]'\nplot " +
                     join(series, ", \\\n     ") + "\nunset key\n");
  }
  if (!run.structure_stretch.t.empty()) {
    write_curve_dat(folder / "data" / "structure_stretch.dat", run.structure_stretch);
    panels.push_back(
        "set ylabel 'stretch (deformation / size)'\nplot 'data/structure_stretch.dat' using 1:2 "
        "with lines\n");
  }
  std::vector<std::string> counts;
  if (!run.coupling_iterations.t.empty()) {
    write_curve_dat(folder / "data" / "coupling_iterations.dat", run.coupling_iterations);
    counts.push_back("'data/coupling_iterations.dat' using 1:2 with steps title 'PPE solves'");
  }
  if (!run.structure_solver_iterations.t.empty()) {
    write_curve_dat(folder / "data" / "structure_solver_iterations.dat",
                    run.structure_solver_iterations);
    counts.push_back(
        "'data/structure_solver_iterations.dat' using 1:2 with steps title 'structure Newton "
        "iterations'");
  }
  if (!counts.empty())
    panels.push_back("set key top left\nset ylabel 'per step'\nplot " +
                     join(counts, ", \\\n     ") + "\nunset key\n");
  if (panels.empty()) return {};
  return fmt::format(
      "set terminal pngcairo noenhanced size 960,{} font ',10'\nset output "
      "'structure_monitors.png'\nunset title\nunset logscale y\nset multiplot layout {},1\n"
      "set grid\nset xlabel 't [s]'\n{}unset multiplot\n",
      300 * panels.size(), panels.size(), join(panels, ""));
}

/// The plots' gnuplot script; data files go to data/.
std::string plot_script(const std::filesystem::path& folder, const RunData& run,
                        const std::vector<Comparison>& cs) {
  std::filesystem::create_directories(folder / "data");
  std::string script;
  for (std::size_t c = 0; c < run.columns.size(); ++c) {
    const std::string stem = file_stem_of(run.columns[c]);
    write_curve_dat(folder / "data" / (stem + ".dat"), run.probes[c]);
    // A probe that never saw fluid has no curve (gnuplot refuses a series of missing values).
    const bool has_values = std::any_of(run.probes[c].v.begin(), run.probes[c].v.end(),
                                        [](double v) { return !std::isnan(v); });
    std::vector<std::string> series;
    if (has_values)
      series.push_back(fmt::format("{} using 1:2 with lines lw 2 title 'hydromodal'",
                                   gnuplot_quoted("data/" + stem + ".dat")));
    for (std::size_t k = 0; k < cs.size(); ++k) {
      if (cs[k].column != run.columns[c]) continue;
      const std::string ref = fmt::format("data/{}.ref{}.dat", stem, k);
      write_curve_dat(folder / ref, cs[k].reference);
      series.push_back(fmt::format("{} using 1:2 with linespoints pt 7 ps 0.5 title {}",
                                   gnuplot_quoted(ref), gnuplot_quoted(cs[k].label)));
    }
    if (series.empty()) {
      spdlog::warn("{}: {} has no value (its probe saw no fluid): no plot", stage_name,
                   run.columns[c]);
      continue;
    }
    const std::string title =
        has_values ? run.columns[c] : run.columns[c] + " (no fluid at the probe during the run)";
    script += plot_header(stem + ".png", title, "t [s]", run.columns[c]);
    script += "plot " + join(series, ", \\\n     ") + "\n";
  }
  if (run.modal.size() > 0) {
    std::ofstream out(folder / "data" / "modal.dat");
    out.precision(17);
    for (Eigen::Index k = 0; k < run.modal.rows(); ++k) {
      out << run.modal_time[static_cast<std::size_t>(k)];
      for (Eigen::Index m = 0; m < run.modal.cols(); ++m) out << ' ' << run.modal(k, m);
      out << '\n';
    }
    script += plot_header("structure.png", "structure: modal coordinates", "t [s]", "y [m·√kg]");
    std::vector<std::string> series;
    for (Eigen::Index m = 0; m < run.modal.cols(); ++m)
      series.push_back(
          fmt::format("'data/modal.dat' using 1:{} with lines title 'mode {}'", m + 2, m + 1));
    script += "plot " + join(series, ", \\\n     ") + "\n";
  }
  if (!run.dt.t.empty()) {
    write_curve_dat(folder / "data" / "dt.dat", run.dt);
    write_curve_dat(folder / "data" / "ppe_iterations.dat", run.ppe_iterations);
    write_curve_dat(folder / "data" / "volume_drift.dat", run.volume_drift);
    script +=
        "set terminal pngcairo noenhanced size 960,900 font ',10'\nset output "
        "'monitors.png'\nunset title\n"
        "set multiplot layout 3,1\nset grid\nunset key\nset xlabel 't [s]'\n"
        "set ylabel 'Δt [s]'\nset logscale y\nplot 'data/dt.dat' using 1:2 with steps\n"
        "unset logscale y\nset ylabel 'PPE iterations'\n"
        "plot 'data/ppe_iterations.dat' using 1:2 with impulses\n"
        "set ylabel 'volume drift [%]'\nplot 'data/volume_drift.dat' using 1:($2*100) with lines\n"
        "unset multiplot\n";
  }
  script += structure_monitor_script(folder, run);
  return script;
}

}  // namespace

CurveMetrics compare_curves(const Curve& run, const Curve& reference, double window_start,
                            double window_end, const std::string& context) {
  if (run.t.empty() || reference.t.empty())
    input_error("{}: an empty curve (run {} samples, reference {})", context, run.t.size(),
                reference.t.size());
  CurveMetrics m;
  // The window, cut to where both curves exist (a reference longer than the run, or a shorter
  // smoke run, is compared where they overlap).
  m.window_start = std::max(
      {run.t.front(), reference.t.front(), std::isnan(window_start) ? -HUGE_VAL : window_start});
  m.window_end =
      std::min({run.t.back(), reference.t.back(), std::isnan(window_end) ? HUGE_VAL : window_end});
  if (!(m.window_end > m.window_start))
    input_error("{}: the run ({}–{} s) and the reference ({}–{} s) do not overlap in the window",
                context, run.t.front(), run.t.back(), reference.t.front(), reference.t.back());
  const auto [p, tp] = peak_in(run, m.window_start, m.window_end);
  const auto [q, tq] = peak_in(reference, m.window_start, m.window_end);
  const bool run_has_samples = std::any_of(run.t.begin(), run.t.end(), [&](double t) {
    return t >= m.window_start && t <= m.window_end;
  });
  if (std::isnan(tq) || !run_has_samples)
    input_error("{}: no sample of the run or the reference in {}–{} s", context, m.window_start,
                m.window_end);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (std::isnan(tp)) {  // every run sample in the window is missing: the probe saw no fluid
    m.without_fluid = true;
    m.peak = m.peak_time = m.peak_error = m.peak_time_error = m.rms = m.rms_relative = nan;
    m.reference_peak = q;
    m.reference_peak_time = tq;
    return m;
  }
  m.peak = p;
  m.peak_time = tp;
  m.reference_peak = q;
  m.reference_peak_time = tq;
  m.peak_error = q != 0.0 ? (p - q) / std::abs(q) : nan;
  m.peak_time_error = tp - tq;
  double sum = 0.0;
  for (std::size_t k = 0; k < reference.t.size(); ++k) {
    if (reference.t[k] < m.window_start || reference.t[k] > m.window_end) continue;
    ++m.samples;
    const double d = interpolate(run, reference.t[k]) - reference.v[k];
    if (std::isnan(d)) {
      ++m.missing;
      continue;
    }
    sum += d * d;
  }
  m.rms = m.samples > m.missing ? std::sqrt(sum / (m.samples - m.missing)) : nan;
  m.rms_relative = q != 0.0 ? m.rms / std::abs(q) : nan;
  return m;
}

Curve read_reference_csv(const std::filesystem::path& file, int time_column, int value_column,
                         double scale, double time_scale, double time_offset) {
  std::ifstream in(file);
  if (!in) input_error("reference file '{}' cannot be read", file.string());
  std::string line;
  std::vector<std::pair<double, double>> rows;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::vector<std::string> fields = split_csv_fields(line);
    if (number == 1 || (fields.size() == 1 && fields[0].empty())) continue;  // header, blank
    const auto need = static_cast<std::size_t>(std::max(time_column, value_column));
    double t = 0, v = 0;
    if (fields.size() <= need || !parse_number(fields[time_column], t) ||
        !parse_number(fields[value_column], v) || !std::isfinite(t) || !std::isfinite(v))
      input_error("{}:{}: expected numbers in columns {} and {} (0-based), got '{}'", file.string(),
                  number, time_column, value_column, line);
    rows.emplace_back(time_scale * t + time_offset, scale * v);
  }
  if (rows.empty()) input_error("reference file '{}' holds no data row", file.string());
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  Curve c;
  for (const auto& [t, v] : rows) {
    c.t.push_back(t);
    c.v.push_back(v);
  }
  return c;
}

Curve read_probe_column(const io::ArtefactReader& results, const std::string& column) {
  RunData run;
  read_probes(results, run);
  const auto it = std::find(run.columns.begin(), run.columns.end(), column);
  if (it == run.columns.end())
    input_error("{}: no probe column \"{}\" (columns: {})", results.path().string(), column,
                join(run.columns, ", "));
  return std::move(run.probes[static_cast<std::size_t>(it - run.columns.begin())]);
}

Curve report_reference(const io::Scene& scene, const std::string& column,
                       const std::string& label) {
  std::vector<std::string> known;
  for (const io::SceneView& view : compare_entries(scene)) {
    const std::string entry_label = view.string("label").empty()
                                        ? view.file_path("file").stem().string()
                                        : view.string("label");
    if (view.string("column") == column && entry_label == label)
      return read_reference_csv(
          view.file_path("file"), static_cast<int>(view.integer("time_column")),
          static_cast<int>(view.integer("value_column")), view.number("scale"),
          view.number("time_scale"), view.number("time_offset"));
    known.push_back(fmt::format("\"{}\" for \"{}\"", entry_label, view.string("column")));
  }
  input_error("{}: no [[report.compare]] entry labelled \"{}\" for the column \"{}\" (entries: {})",
              scene.file().string(), label, column, known.empty() ? "none" : join(known, ", "));
}

std::pair<double, double> report_window_bounds(const io::Scene& scene) {
  const Eigen::VectorXd window = report_window(scene);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return window.size() == 2 ? std::pair{window[0], window[1]} : std::pair{nan, nan};
}

void validate_report_scene(const io::Scene& scene) {
  for (const io::SceneView& view : compare_entries(scene))
    if (!std::filesystem::exists(view.file_path("file")))
      input_error("{}: reference file '{}' does not exist", view.where("file"),
                  view.file_path("file").string());
  const Eigen::VectorXd window = report_window(scene);
  if (window.size() != 0 && (window.size() != 2 || !(window[1] > window[0])))
    input_error("{}: give [t0, t1] with t1 > t0 (s), or leave it empty",
                scene.where("report.window"));
}

void run_report_stage(const io::Scene& scene, const std::filesystem::path& results,
                      const std::filesystem::path& output) {
  validate_report_scene(scene);
  const RunData run = read_run(results);
  const std::vector<Comparison> cs = comparisons(scene, run);
  const auto [window_start, window_end] = report_window_bounds(scene);
  std::vector<CurveMetrics> ms;
  for (const Comparison& c : cs) {
    const auto column = static_cast<std::size_t>(
        std::find(run.columns.begin(), run.columns.end(), c.column) - run.columns.begin());
    ms.push_back(compare_curves(run.probes[column], c.reference, window_start, window_end,
                                fmt::format("{} against {}", c.column, c.file.string())));
    if (ms.back().without_fluid)
      spdlog::warn(
          "{}: {} has no value in the window (its probe saw no fluid): its metrics against {} "
          "are missing (NaN; probe_without_fluid in metrics.json)",
          stage_name, c.column, c.label);
  }

  // Everything is written into a fresh folder beside the report's and renamed over it.
  const std::filesystem::path folder = output.parent_path().empty() ? "." : output.parent_path();
  write_folder_atomically(folder, [&](const std::filesystem::path& staging) {
    run_gnuplot(staging, plot_script(staging, run, cs), stage_name);
    {
      std::ofstream json(staging / "metrics.json");
      json << metrics_json(cs, ms).dump(2) << '\n';
      std::ofstream md(staging / "metrics.md");
      md << "# " << scene.string("case.name") << ": error against the references\n\n"
         << metrics_markdown(cs, ms);
    }
    std::vector<io::InputRecord> records{io::input_record("results", results)};
    for (std::size_t k = 0; k < cs.size(); ++k)
      records.push_back(io::input_record(fmt::format("reference_{}", k), cs[k].file));
    io::ArtefactWriter w(staging / output.filename(), io::report_schema(), stage_name,
                         scene.parameters_for(stage_name), records);
    io::MatrixRM table(static_cast<Eigen::Index>(ms.size()), 10);
    std::vector<std::string> labels;
    for (std::size_t k = 0; k < ms.size(); ++k) {
      const auto& m = ms[k];
      table.row(static_cast<Eigen::Index>(k)) << m.peak, m.peak_time, m.reference_peak,
          m.reference_peak_time, m.peak_error, m.peak_time_error, m.rms, m.rms_relative,
          m.window_start, m.window_end;
      labels.push_back(cs[k].column + " vs " + cs[k].label);
    }
    if (table.rows() > 0) w.write("/comparisons/metrics", table);
    w.set_attribute("comparison_labels", join(labels, "\n"));
    w.commit();
  });
  spdlog::info("{}: {} plot(s) and {} comparison(s) in {}:\n{}", stage_name,
               run.columns.size() + (run.modal.size() > 0) + !run.dt.t.empty(), cs.size(),
               folder.string(), metrics_markdown(cs, ms));
}

}  // namespace hm::driver
