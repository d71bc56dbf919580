#pragma once
// Probe time series as CSV: comma-separated, one header line, first column `t [s]`, every other
// column `<probe>.<quantity> [unit]` (e.g. `gauge1.eta [m]`, `P1.p [Pa]`), one row per output
// time. Numbers are written with the shortest text that reads back to the same double.
//
// Kill-safety: rows go straight to `<path>.partial`, flushed after each row, so a killed run
// keeps every row it wrote (readable with read_probe_csv); finish() renames the file to `<path>`.
// So `<path>` exists only for a run that finished, and a `.partial` file is a run that did not.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hm::io {

class ProbeCsvWriter {
 public:
  /// Opens `<path>.partial` (creating the folder) and writes the header. Removes a stale `<path>`
  /// of an earlier run. InputError when a column name is not `<probe>.<quantity> [unit]` or holds
  /// a comma, quote or line break, or when the file cannot be written.
  ProbeCsvWriter(std::filesystem::path path, std::vector<std::string> columns);
  ~ProbeCsvWriter();  ///< closes; an unfinished file stays at `<path>.partial`
  ProbeCsvWriter(const ProbeCsvWriter&) = delete;
  ProbeCsvWriter& operator=(const ProbeCsvWriter&) = delete;

  /// One row: time t [s] and one value per column (values.size() == columns().size()).
  void write_row(double t, std::span<const double> values);
  /// Closes the file and renames `<path>.partial` to `<path>`.
  void finish();

  const std::vector<std::string>& columns() const { return columns_; }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path partial_path() const;

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::unique_ptr<std::FILE, Closer> file_;
};

/// Header text of the time column.
inline constexpr std::string_view probe_time_column = "t [s]";

/// Whether `name` has the form `<probe>.<quantity> [unit]` (no comma, quote or line break).
bool is_probe_column_name(std::string_view name);

struct ProbeTable {
  std::vector<std::string> names;            ///< header, names[0] == "t [s]"
  std::vector<std::vector<double>> columns;  ///< columns[c][row], same order as names
  std::size_t rows() const { return columns.empty() ? 0 : columns[0].size(); }
  /// The column named `name`; InputError listing the names when there is none.
  const std::vector<double>& column(std::string_view name) const;
};

/// Reads a probe CSV (a finished file or a `.partial` one). InputError naming the file, line and
/// column on a missing file, a bad header or a malformed row. A last line without a line break
/// that does not parse is a row cut off by a killed run and is dropped.
ProbeTable read_probe_csv(const std::filesystem::path& path);

}  // namespace hm::io
