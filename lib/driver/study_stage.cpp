#include "driver/study_stage.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/text.hpp"
#include "core/version.hpp"
#include "driver/gnuplot.hpp"
#include "driver/metrics_json.hpp"
#include "driver/report_stage.hpp"
#include "driver/simulate_stage.hpp"
#include "io/artefact.hpp"
#include "io/scene.hpp"
#include "io/schema.hpp"

namespace hm::driver {
namespace {

constexpr const char* stage_name = "fsi-study";
constexpr double nan = std::numeric_limits<double>::quiet_NaN();
namespace ra = io::results_attr;

// ---- the study file ----------------------------------------------------------------------------

/// Reads one table of the study file, refusing keys it does not know.
class StudyTable {
 public:
  StudyTable(const toml::table& table, std::string where, const std::filesystem::path& file,
             const std::set<std::string>& known)
      : table_(table), where_(std::move(where)), file_(file) {
    for (const auto& [key, node] : table)
      if (!known.contains(std::string(key.str())))
        input_error("{}:{}: unknown key '{}{}' in the study; known keys here: {}", file.string(),
                    node.source().begin.line, where_, key.str(),
                    join(std::vector<std::string>(known.begin(), known.end()), ", "));
  }

  std::string string(const std::string& key, bool required = true) const {
    const toml::node* node = table_.get(key);
    if (!node) {
      if (required) input_error("{}: missing key '{}{}' (a string)", file_.string(), where_, key);
      return "";
    }
    if (!node->is_string())
      input_error("{}:{}: '{}{}' must be a string", file_.string(), node->source().begin.line,
                  where_, key);
    return node->as_string()->get();
  }

  std::vector<std::string> strings(const std::string& key) const {
    std::vector<std::string> out;
    const toml::node* node = table_.get(key);
    if (!node) return out;
    const auto* array = node->as_array();
    if (!array || !std::all_of(array->begin(), array->end(),
                               [](const toml::node& e) { return e.is_string(); }))
      input_error("{}:{}: '{}{}' must be an array of \"key=value\" strings", file_.string(),
                  node->source().begin.line, where_, key);
    for (const auto& element : *array) out.push_back(element.as_string()->get());
    return out;
  }

  std::vector<const toml::table*> tables(const std::string& key) const {
    const toml::node* node = table_.get(key);
    const auto* array = node ? node->as_array() : nullptr;
    if (!array || array->empty() || !array->is_array_of_tables())
      input_error("{}: '{}{}' must be a non-empty array of tables", file_.string(), where_, key);
    std::vector<const toml::table*> out;
    for (const auto& element : *array) out.push_back(element.as_table());
    return out;
  }

 private:
  const toml::table& table_;
  std::string where_;
  const std::filesystem::path& file_;
};

void check_name(const std::string& name, const std::string& what,
                const std::filesystem::path& file) {
  const bool ok = !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '-';
  });
  if (!ok)
    input_error("{}: {} = \"{}\": use letters, digits, '.', '_' and '-' only (it names a folder)",
                file.string(), what, name);
}

/// The key of a "key=value" setting.
std::string setting_key(const std::string& setting) {
  return std::string(trimmed(std::string_view(setting).substr(0, setting.find('='))));
}

/// The value text the run's settings give `parameter` (the last one wins, as in --set).
std::string parameter_value(const StudyRun& run, const std::string& parameter,
                            const std::string& where, const std::filesystem::path& file) {
  std::string value;
  for (const auto& setting : run.set) {
    if (setting.find('=') == std::string::npos)
      input_error("{}: {}: the setting \"{}\" is not key=value", file.string(), where, setting);
    if (setting.find_first_of(" \t") != std::string::npos)
      input_error("{}: {}: the setting \"{}\" holds a blank (write arrays as [0.0,0.01])",
                  file.string(), where, setting);
    if (setting_key(setting) == parameter) value = setting.substr(setting.find('=') + 1);
  }
  if (value.empty())
    input_error("{}: {}: its settings do not set the series' parameter '{}'", file.string(), where,
                parameter);
  return value;
}

// ---- collecting the runs -----------------------------------------------------------------------

struct RunOutcome {
  const StudyRun* run = nullptr;
  std::filesystem::path folder;
  double value = nan;  ///< the parameter as a number (NaN when it is none)
  std::string status;
  double simulate_seconds = 0.0, modes_seconds = 0.0;
  long long steps = 0, points = 0;
  Curve probe;
  CurveMetrics vs_reference, vs_last;
  double order = nan;  ///< from the previous run of the series
};

/// A series' runs, and the reference they are measured against (empty without one).
struct SeriesOutcome {
  std::vector<RunOutcome> runs;
  Curve reference;
};

double time_to_solution(const RunOutcome& r) {
  return r.simulate_seconds + r.modes_seconds;
}

/// Refuses results made with other settings than the study now gives the run (a run whose
/// remake failed keeps its old results.h5); another tool version is only a warning.
void check_run_is_current(const io::ArtefactReader& reader, const io::Scene& scene,
                          const std::string& run_name, const std::filesystem::path& results,
                          const std::filesystem::path& study_file) {
  const io::Provenance& p = reader.provenance();
  if (p.parameters != simulate_parameters(scene, !scene.has("structure")))
    input_error(
        "{}: run {} is stale: {} was made with other scene parameters than the run's settings "
        "give now (did its last make fail?); make it again with make -C {}",
        study_file.string(), run_name, results.string(), study_file.parent_path().string());
  if (p.tool_version != tool_version())
    spdlog::warn("{}: run {} was made by tool version {}, this is {}", stage_name, run_name,
                 p.tool_version, tool_version());
}

RunOutcome read_outcome(const Study& study, const StudySeries& series, const StudyRun& run,
                        const io::Scene& scene, const std::filesystem::path& runs) {
  RunOutcome r;
  r.run = &run;
  r.folder = runs / series.name / run.name;
  const auto results = r.folder / "results.h5";
  if (!std::filesystem::exists(results))
    input_error("{}: run {}/{} has no results ({} is missing); make it with make -C {}",
                study.file.string(), series.name, run.name, results.string(),
                study.file.parent_path().string());
  {
    const io::ArtefactReader reader(results, io::results_schema());
    check_run_is_current(reader, scene, series.name + "/" + run.name, results, study.file);
    r.status = reader.string_attribute(ra::run_status).value_or("?");
    r.simulate_seconds = reader.number_attribute(ra::wall_seconds).value_or(nan);
    r.steps = static_cast<long long>(reader.number_attribute(ra::steps).value_or(0));
    r.points = static_cast<long long>(reader.number_attribute(ra::points).value_or(0));
    r.probe = read_probe_column(reader, study.column);
  }
  if (const auto modes = r.folder / "modes.h5"; std::filesystem::exists(modes)) {
    const io::ArtefactReader reader(modes, io::modes_schema());
    r.modes_seconds = reader.number_attribute(io::modes_attr::factorisation_seconds).value_or(0.0) +
                      reader.number_attribute(io::modes_attr::lanczos_seconds).value_or(0.0);
  }
  parse_number(run.value, r.value);
  return r;
}

/// The metrics of every run of a series: against the reference and against the last run. The
/// reference is read once, from the case's scene with the last run's settings.
SeriesOutcome collect_series(const Study& study, const StudySeries& series,
                             const std::filesystem::path& runs) {
  SeriesOutcome out;
  std::vector<std::pair<double, double>> windows;  // report.window of each run [s]
  for (const StudyRun& run : series.runs) {
    const io::Scene scene = io::Scene::load(study.scene, run.set);
    out.runs.push_back(read_outcome(study, series, run, scene, runs));
    windows.push_back(report_window_bounds(scene));
    if (&run == &series.runs.back() && !study.reference.empty())
      out.reference = report_reference(scene, study.column, study.reference);
  }
  const RunOutcome& last = out.runs.back();
  for (std::size_t k = 0; k < out.runs.size(); ++k) {
    RunOutcome& r = out.runs[k];
    const auto [t0, t1] = windows[k];
    const std::string context =
        fmt::format("{}: run {}/{}", study.file.string(), series.name, r.run->name);
    if (!study.reference.empty())
      r.vs_reference =
          compare_curves(r.probe, out.reference, t0, t1, context + " against " + study.reference);
    r.vs_last = compare_curves(r.probe, last.probe, windows.back().first, windows.back().second,
                               context + " against run " + last.run->name);
    if (k > 0 && k + 1 < out.runs.size())
      r.order = observed_order(out.runs[k - 1].value, out.runs[k - 1].vs_last.rms_relative, r.value,
                               r.vs_last.rms_relative);
  }
  return out;
}

// ---- writing -----------------------------------------------------------------------------------

std::string percent(double relative) {
  return std::isfinite(relative) ? fmt::format("{:+.1f} %", 100 * relative) : "—";
}
std::string unsigned_percent(double relative) {
  return std::isfinite(relative) ? fmt::format("{:.2f} %", 100 * relative) : "—";
}

std::string series_markdown(const Study& study, const StudySeries& series,
                            const SeriesOutcome& outcome) {
  const std::string last = series.runs.back().name;
  std::string md = fmt::format(
      "## {} (`{}`)\n\n| run | {} | points | steps | status | time to solution [s] | of it "
      "modes [s] | peak | peak error | Δt of peak [s] | RMS / \\|ref. peak\\| | RMS vs {} | "
      "order |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n",
      series.name, series.parameter, series.parameter, last);
  for (const RunOutcome& r : outcome.runs) {
    const bool has_ref = !study.reference.empty();
    md += fmt::format(
        "| {} | {} | {} | {} | {} | {:.1f} | {:.2f} | {:.4g} | {} | {} | {} | {} | {} |\n",
        r.run->name, r.run->value, r.points, r.steps, r.status, time_to_solution(r),
        r.modes_seconds, r.vs_last.peak, has_ref ? percent(r.vs_reference.peak_error) : "—",
        has_ref ? fmt::format("{:+.4f}", r.vs_reference.peak_time_error) : "—",
        has_ref ? unsigned_percent(r.vs_reference.rms_relative) : "—",
        r.run == &series.runs.back() ? "(itself)" : unsigned_percent(r.vs_last.rms_relative),
        std::isfinite(r.order) ? fmt::format("{:.2f}", r.order) : "—");
  }
  return md;
}

nlohmann::ordered_json series_json(const Study& study, const StudySeries& series,
                                   const SeriesOutcome& outcome) {
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const RunOutcome& r : outcome.runs) {
    nlohmann::ordered_json j = {{"name", r.run->name},
                                {"value", r.run->value},
                                {"set", r.run->set},
                                {"folder", r.folder.string()},
                                {"status", r.status},
                                {"points", r.points},
                                {"steps", r.steps},
                                {"simulate_seconds", r.simulate_seconds},
                                {"modes_seconds", r.modes_seconds},
                                {"time_to_solution_s", time_to_solution(r)},
                                {"peak", r.vs_last.peak},
                                {"peak_time_s", r.vs_last.peak_time}};
    if (!study.reference.empty()) j["vs_reference"] = curve_metrics_json(r.vs_reference);
    j["vs_last"] = curve_metrics_json(r.vs_last);
    j["order"] = std::isfinite(r.order) ? nlohmann::ordered_json(r.order) : nullptr;
    runs.push_back(std::move(j));
  }
  return {{"name", series.name}, {"parameter", series.parameter}, {"runs", std::move(runs)}};
}

/// Two plots per series: time to solution against the errors (log–log), and the probe of every
/// run against the reference.
std::string series_plots(const Study& study, const StudySeries& series,
                         const SeriesOutcome& outcome, const std::filesystem::path& folder) {
  const auto data = folder / "data";
  std::filesystem::create_directories(data);
  const std::string cost_file = "data/" + series.name + ".cost.dat";
  {
    std::ofstream out(folder / cost_file);
    out.precision(17);
    out << "# run time_to_solution_s rms_vs_reference_percent rms_vs_last_percent\n";
    for (const RunOutcome& r : outcome.runs) {
      const bool is_last = r.run == &series.runs.back();
      out << r.run->name << ' ' << time_to_solution(r) << ' '
          << (study.reference.empty() ? nan : 100 * r.vs_reference.rms_relative) << ' '
          << (is_last ? nan : 100 * r.vs_last.rms_relative) << '\n';
    }
  }
  std::string script = plot_header(
      series.name + ".cost.png",
      fmt::format("{}: time to solution against error ({})", series.name, series.parameter),
      "time to solution [s]", "RMS error / |peak| [%]");
  script += "set logscale xy\nset key top right\n";
  std::vector<std::string> lines;
  if (!study.reference.empty())
    lines.push_back(fmt::format(
        "{0} using 2:3 with linespoints pt 7 lw 2 title {1}, {0} using 2:3:1 with labels "
        "offset 1,0.7 notitle",
        gnuplot_quoted(cost_file), gnuplot_quoted("against " + study.reference)));
  lines.push_back(
      fmt::format("{0} using 2:4 with linespoints pt 5 lw 2 title {1}, {0} using 2:4:1 with labels "
                  "offset 1,-0.7 notitle",
                  gnuplot_quoted(cost_file),
                  gnuplot_quoted("against run " + series.runs.back().name + " (the finest)")));
  script += "plot " + join(lines, ", \\\n     ") + "\nunset logscale xy\n";

  std::vector<std::string> curves;
  for (const RunOutcome& r : outcome.runs) {
    const std::string file = fmt::format("data/{}.{}.dat", series.name, r.run->name);
    write_curve_dat(folder / file, r.probe);
    curves.push_back(fmt::format(
        "{} using 1:2 with lines lw 2 title {}", gnuplot_quoted(file),
        gnuplot_quoted(fmt::format("{} ({} = {})", r.run->name, series.parameter, r.run->value))));
  }
  if (!study.reference.empty()) {
    const std::string file = fmt::format("data/{}.reference.dat", series.name);
    write_curve_dat(folder / file, outcome.reference);
    curves.push_back(fmt::format("{} using 1:2 with linespoints pt 7 ps 0.6 title {}",
                                 gnuplot_quoted(file), gnuplot_quoted(study.reference)));
  }
  script +=
      plot_header(series.name + ".curves.png",
                  fmt::format("{}: {} at each {}", series.name, study.column, series.parameter),
                  "t [s]", study.column);
  script += "set key below\nplot " + join(curves, ", \\\n     ") + "\n";
  return script;
}

}  // namespace

Study load_study(const std::filesystem::path& file) {
  toml::table root;
  try {
    root = toml::parse_file(file.string());
  } catch (const toml::parse_error& e) {
    input_error("{}:{}:{}: TOML syntax error: {}", file.string(), e.source().begin.line,
                e.source().begin.column, e.description());
  }
  const StudyTable top(root, "", file, {"scene", "column", "reference", "set", "series"});
  Study study;
  study.file = file;
  study.scene = file.parent_path() / top.string("scene");
  if (!std::filesystem::exists(study.scene))
    input_error("{}: scene = \"{}\": no such file ({})", file.string(), top.string("scene"),
                study.scene.string());
  study.column = top.string("column");
  study.reference = top.string("reference", false);
  const std::vector<std::string> common = top.strings("set");
  std::set<std::string> series_names;
  const auto series_tables = top.tables("series");
  for (std::size_t s = 0; s < series_tables.size(); ++s) {
    const StudyTable table(*series_tables[s], fmt::format("series[{}].", s), file,
                           {"name", "parameter", "set", "runs"});
    StudySeries series{table.string("name"), table.string("parameter"), {}};
    check_name(series.name, fmt::format("series[{}].name", s), file);
    if (!series_names.insert(series.name).second)
      input_error("{}: two series are named \"{}\"", file.string(), series.name);
    std::vector<std::string> series_set = common;
    for (const auto& setting : table.strings("set")) series_set.push_back(setting);
    std::set<std::string> run_names;
    const auto run_tables = table.tables("runs");
    for (std::size_t r = 0; r < run_tables.size(); ++r) {
      const std::string where = fmt::format("series[{}].runs[{}].", s, r);
      const StudyTable run_table(*run_tables[r], where, file, {"name", "set"});
      StudyRun run{run_table.string("name"), series_set, ""};
      check_name(run.name, where + "name", file);
      if (!run_names.insert(run.name).second)
        input_error("{}: series \"{}\" has two runs named \"{}\"", file.string(), series.name,
                    run.name);
      for (const auto& setting : run_table.strings("set")) run.set.push_back(setting);
      run.value = parameter_value(run, series.parameter,
                                  fmt::format("run {}/{}", series.name, run.name), file);
      series.runs.push_back(std::move(run));
    }
    study.series.push_back(std::move(series));
  }
  // Every run's scene must load: a bad key or value is reported now, not after hours of runs.
  for (const auto& series : study.series)
    for (const auto& run : series.runs) {
      const io::Scene scene = io::Scene::load(study.scene, run.set);
      if (!study.reference.empty()) report_reference(scene, study.column, study.reference);
    }
  return study;
}

std::string study_make_rules(const Study& study) {
  const auto scene = std::filesystem::absolute(study.scene).lexically_normal();
  std::string out = fmt::format(
      "# Generated by fsi-study from {}; do not edit.\nSTUDY_SCENE := {}\nSTUDY_CASE_DIR := {}\n",
      study.file.string(), scene.string(), scene.parent_path().string());
  std::vector<std::string> runs;
  for (const auto& series : study.series)
    for (const auto& run : series.runs) {
      runs.push_back(series.name + "/" + run.name);
      out += fmt::format("STUDY_SET.{}/{} := {}\n", series.name, run.name, join(run.set, " "));
    }
  out += "STUDY_RUNS := " + join(runs, " ") + "\n";
  return out;
}

double observed_order(double value0, double error0, double value1, double error1) {
  if (!(value0 > 0) || !(value1 > 0) || value0 == value1 || !(error0 > 0) || !(error1 > 0))
    return nan;
  return std::log(error0 / error1) / std::abs(std::log(value0 / value1));
}

void run_study_stage(const Study& study, const std::filesystem::path& runs,
                     const std::filesystem::path& output) {
  std::vector<SeriesOutcome> outcomes;
  for (const auto& series : study.series) outcomes.push_back(collect_series(study, series, runs));

  std::string md = fmt::format(
      "# Speed against error: {}\n\nCase `{}`, probe column `{}`{}. Time to solution: "
      "fsi-simulate's wall time plus fsi-modes' solve. RMS errors over report.window, relative "
      "to the |peak| of the reference (or of the series' last run); the order is observed "
      "between a run and the one before it, against the series' last run.\n\n",
      study.file.parent_path().filename().string(), study.scene.lexically_normal().string(),
      study.column,
      study.reference.empty() ? "" : fmt::format(", reference \"{}\"", study.reference));
  nlohmann::ordered_json json = {{"study", study.file.string()},
                                 {"scene", study.scene.string()},
                                 {"column", study.column},
                                 {"reference", study.reference},
                                 {"series", nlohmann::ordered_json::array()}};
  for (std::size_t s = 0; s < study.series.size(); ++s) {
    md += series_markdown(study, study.series[s], outcomes[s]) + "\n";
    json["series"].push_back(series_json(study, study.series[s], outcomes[s]));
  }

  const std::filesystem::path folder = output.parent_path().empty() ? "." : output.parent_path();
  write_folder_atomically(folder, [&](const std::filesystem::path& staging) {
    std::string script;
    for (std::size_t s = 0; s < study.series.size(); ++s)
      script += series_plots(study, study.series[s], outcomes[s], staging);
    run_gnuplot(staging, script, stage_name);
    std::ofstream(staging / "study.md") << md;
    std::ofstream out(staging / output.filename());
    out << json.dump(2) << '\n';
    if (!out) input_error("{}: cannot write {}", stage_name, output.string());
  });
  spdlog::info("{}: {} series tabulated and plotted in {}", stage_name, study.series.size(),
               folder.string());
}

}  // namespace hm::driver
