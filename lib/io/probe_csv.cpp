#include "io/probe_csv.hpp"

#include <charconv>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text.hpp"

namespace hm::io {
namespace {

void write_or_throw(std::FILE* file, const std::string& text, const std::filesystem::path& path) {
  if (std::fwrite(text.data(), 1, text.size(), file) != text.size() || std::fflush(file) != 0)
    input_error("cannot write the probe file '{}'", path.string());
}

/// Parses one data row; "" on success, else what is wrong (naming line and column).
std::string parse_row(std::string_view line, std::size_t line_number, ProbeTable& table) {
  const auto fields = split_csv_fields(line);
  if (fields.size() != table.names.size())
    return fmt::format("line {} has {} fields, the header has {} columns", line_number,
                       fields.size(), table.names.size());
  std::vector<double> values(fields.size());
  for (std::size_t c = 0; c < fields.size(); ++c)
    if (!parse_number(fields[c], values[c]))
      return fmt::format("line {}, column {} ('{}'): '{}' is not a number", line_number, c + 1,
                         table.names[c], fields[c]);
  for (std::size_t c = 0; c < fields.size(); ++c) table.columns[c].push_back(values[c]);
  return "";
}

}  // namespace

bool is_probe_column_name(std::string_view name) {
  if (name.find_first_of(",\"\r\n") != std::string_view::npos) return false;
  const std::size_t bracket = name.rfind(" [");
  if (bracket == std::string_view::npos || name.back() != ']' || bracket + 3 >= name.size())
    return false;
  const std::string_view label = name.substr(0, bracket);
  const std::size_t dot = label.rfind('.');
  return dot != std::string_view::npos && dot > 0 && dot + 1 < label.size();
}

ProbeCsvWriter::ProbeCsvWriter(std::filesystem::path path, std::vector<std::string> columns)
    : path_(std::move(path)), columns_(std::move(columns)) {
  for (std::size_t c = 0; c < columns_.size(); ++c)
    if (!is_probe_column_name(columns_[c]))
      input_error(
          "probe file '{}': column {} '{}' is not of the form '<probe>.<quantity> [unit]' "
          "(e.g. 'gauge1.eta [m]'; no comma, quote or line break)",
          path_.string(), c + 2, columns_[c]);
  std::error_code ec;
  if (path_.has_parent_path()) std::filesystem::create_directories(path_.parent_path(), ec);
  std::filesystem::remove(path_, ec);  // a stale result of an earlier run
  file_.reset(std::fopen(partial_path().c_str(), "w"));
  if (!file_) input_error("cannot create the probe file '{}'", partial_path().string());
  std::string header(probe_time_column);
  for (const auto& c : columns_) header += "," + c;
  write_or_throw(file_.get(), header + "\n", partial_path());
}

ProbeCsvWriter::~ProbeCsvWriter() = default;

std::filesystem::path ProbeCsvWriter::partial_path() const {
  return std::filesystem::path(path_.string() + ".partial");
}

void ProbeCsvWriter::write_row(double t, std::span<const double> values) {
  HM_ASSERT(file_, "write_row after finish on '{}'", path_.string());
  HM_ASSERT(values.size() == columns_.size(), "'{}': {} values for {} columns", path_.string(),
            values.size(), columns_.size());
  std::string row = fmt::format("{}", t);
  for (double v : values) row += fmt::format(",{}", v);
  write_or_throw(file_.get(), row + "\n", partial_path());
}

void ProbeCsvWriter::finish() {
  HM_ASSERT(file_, "finish called twice on '{}'", path_.string());
  if (std::fclose(file_.release()) != 0)
    input_error("cannot close the probe file '{}'", partial_path().string());
  std::error_code ec;
  std::filesystem::rename(partial_path(), path_, ec);
  if (ec)
    input_error("cannot rename '{}' to '{}': {}", partial_path().string(), path_.string(),
                ec.message());
}

const std::vector<double>& ProbeTable::column(std::string_view name) const {
  for (std::size_t c = 0; c < names.size(); ++c)
    if (names[c] == name) return columns[c];
  input_error("probe table has no column '{}'; it has: {}", name, join(names, ", "));
}

ProbeTable read_probe_csv(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) input_error("cannot open the probe file '{}'", path.string());
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string_view all(text);
  const std::string file = path.string();

  ProbeTable table;
  std::size_t start = 0, line_number = 0;
  while (start < all.size()) {
    const std::size_t end = all.find('\n', start);
    const bool terminated = end != std::string_view::npos;
    const std::string_view line = all.substr(start, terminated ? end - start : all.size() - start);
    start = terminated ? end + 1 : all.size();
    ++line_number;
    if (line_number == 1) {
      table.names = split_csv_fields(line);
      if (table.names[0] != probe_time_column)
        input_error("probe file '{}', line 1, column 1: '{}' should be '{}'", file, table.names[0],
                    probe_time_column);
      for (std::size_t c = 1; c < table.names.size(); ++c)
        if (!is_probe_column_name(table.names[c]))
          input_error(
              "probe file '{}', line 1, column {}: '{}' is not of the form "
              "'<probe>.<quantity> [unit]'",
              file, c + 1, table.names[c]);
      table.columns.resize(table.names.size());
      continue;
    }
    if (line.find_first_not_of(" \t\r") == std::string_view::npos) continue;
    const std::string problem = parse_row(line, line_number, table);
    if (problem.empty()) continue;
    if (!terminated) break;  // cut off by a killed run
    input_error("probe file '{}': {}", file, problem);
  }
  if (table.names.empty()) input_error("probe file '{}' is empty: no header line", file);
  return table;
}

}  // namespace hm::io
