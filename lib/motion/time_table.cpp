#include "motion/time_table.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <string_view>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "core/errors.hpp"
#include "core/text.hpp"

namespace hm::motion {
namespace {

const std::vector<std::string>& accepted_columns() {
  static const std::vector<std::string> names{"x [m]", "y [m]", "z [m]", "theta [rad]",
                                              "theta [deg]"};
  return names;
}

void check_header(const std::string& file, const std::vector<std::string>& header,
                  const std::vector<std::string>& ok) {
  if (header.empty() || header.front() != "t [s]")
    input_error("{}:1: first header column is '{}', expected 't [s]'", file,
                header.empty() ? "" : header.front());
  if (header.size() < 2)
    input_error("{}:1: no column after 't [s]'; expected one or more of {}", file, join(ok, ", "));
  std::set<std::string> seen;
  bool has_angle = false;
  for (std::size_t k = 1; k < header.size(); ++k) {
    const auto& name = header[k];
    if (std::find(ok.begin(), ok.end(), name) == ok.end()) {
      const auto guess = closest_match(name, ok);
      input_error("{}:1: unknown column '{}' (column {}){}; accepted: t [s], {}", file, name, k + 1,
                  guess.empty() ? "" : fmt::format(", did you mean '{}'?", guess), join(ok, ", "));
    }
    const bool angle = name.starts_with("theta");
    if (!seen.insert(name).second || (angle && has_angle))
      input_error("{}:1: column '{}' (column {}) given twice; each column at most once", file, name,
                  k + 1);
    has_angle = has_angle || angle;
  }
}

double parse_number(const std::string& file, std::size_t line, std::size_t column,
                    const std::string& header, const std::string& field) {
  double value = 0.0;
  if (!hm::parse_number(field, value) || !std::isfinite(value))
    input_error("{}:{}: value '{}' in column {} ('{}') is not a finite number", file, line, field,
                column, header);
  return value;
}

}  // namespace

CubicSpline::CubicSpline(std::vector<double> t, std::vector<double> y)
    : t_(std::move(t)), y_(std::move(y)), m_(t_.size(), 0.0) {
  const auto n = static_cast<Eigen::Index>(t_.size());
  HM_ASSERT(n >= 4 && y_.size() == t_.size(), "spline needs >= 4 knots, got {}", n);
  std::vector<double> h(t_.size() - 1);
  for (std::size_t i = 0; i + 1 < t_.size(); ++i) h[i] = t_[i + 1] - t_[i];
  // Unknowns: second derivatives m_i. Interior rows: continuity of the first derivative.
  // First/last rows: not-a-knot, the third derivative is continuous at knots 1 and n−2.
  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
  a.emplace_back(0, 0, h[1]);
  a.emplace_back(0, 1, -(h[0] + h[1]));
  a.emplace_back(0, 2, h[0]);
  for (Eigen::Index i = 1; i + 1 < n; ++i) {
    const auto u = static_cast<std::size_t>(i);
    a.emplace_back(i, i - 1, h[u - 1]);
    a.emplace_back(i, i, 2.0 * (h[u - 1] + h[u]));
    a.emplace_back(i, i + 1, h[u]);
    rhs(i) = 6.0 * ((y_[u + 1] - y_[u]) / h[u] - (y_[u] - y_[u - 1]) / h[u - 1]);
  }
  const auto k = static_cast<std::size_t>(n) - 1;
  a.emplace_back(n - 1, n - 3, h[k - 1]);
  a.emplace_back(n - 1, n - 2, -(h[k - 2] + h[k - 1]));
  a.emplace_back(n - 1, n - 1, h[k - 2]);
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(a.begin(), a.end());
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu(matrix);
  HM_ASSERT(lu.info() == Eigen::Success, "not-a-knot spline matrix is singular");
  const Eigen::VectorXd m = lu.solve(rhs);
  for (Eigen::Index i = 0; i < n; ++i) m_[static_cast<std::size_t>(i)] = m(i);
}

Jet CubicSpline::operator()(double t) const {
  HM_ASSERT(t >= t_.front() && t <= t_.back(), "t = {} outside [{}, {}]", t, t_.front(), t_.back());
  const auto it = std::upper_bound(t_.begin(), t_.end() - 1, t);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - t_.begin() - 1, 0));
  const double h = t_[i + 1] - t_[i];
  const double p = t_[i + 1] - t;  // distance to the right knot
  const double q = t - t_[i];      // distance to the left knot
  const double left = y_[i] / h - m_[i] * h / 6.0;
  const double right = y_[i + 1] / h - m_[i + 1] * h / 6.0;
  return {m_[i] * p * p * p / (6.0 * h) + m_[i + 1] * q * q * q / (6.0 * h) + left * p + right * q,
          -m_[i] * p * p / (2.0 * h) + m_[i + 1] * q * q / (2.0 * h) - left + right,
          (m_[i] * p + m_[i + 1] * q) / h};
}

TimeTable read_time_table(const std::filesystem::path& path) {
  return read_time_table(path, accepted_columns());
}

TimeTable read_time_table(const std::filesystem::path& path,
                          const std::vector<std::string>& accepted) {
  TimeTable table;
  table.file = path.string();
  const auto& file = table.file;
  std::ifstream in(path);
  if (!in)
    input_error(
        "motion table '{}' cannot be opened: expected a readable CSV file with header "
        "'t [s], ...'",
        file);
  std::string line;
  if (!std::getline(in, line))
    input_error("{}:1: file is empty; expected a header line starting with 't [s]'", file);
  const auto header = split_csv_fields(line);
  check_header(file, header, accepted);
  table.columns.assign(header.begin() + 1, header.end());
  table.values.resize(table.columns.size());
  for (std::size_t number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = split_csv_fields(line);
    if (fields.size() != header.size())
      input_error("{}:{}: {} comma-separated values, expected {} (one per header column: {})", file,
                  number, fields.size(), header.size(), join(header, ", "));
    const double t = parse_number(file, number, 1, header[0], fields[0]);
    if (!table.time.empty() && !(t > table.time.back()))
      input_error(
          "{}:{}: time {} s is not greater than the previous time {} s; times must be "
          "strictly increasing",
          file, number, t, table.time.back());
    table.time.push_back(t);
    for (std::size_t k = 1; k < fields.size(); ++k)
      table.values[k - 1].push_back(parse_number(file, number, k + 1, header[k], fields[k]));
  }
  if (table.time.size() < 4)
    input_error("{}: {} data rows, expected at least 4 (cubic spline interpolation)", file,
                table.time.size());
  return table;
}

ScalarLaw table_law(const TimeTable& table, std::size_t column, double scale) {
  HM_ASSERT(column < table.values.size(), "column {} out of range", column);
  std::vector<double> y = table.values[column];
  for (double& v : y) v *= scale;
  auto spline = std::make_shared<const CubicSpline>(table.time, std::move(y));
  return [spline, file = table.file](double t) {
    if (!(t >= spline->t_first() && t <= spline->t_last()))
      input_error(
          "motion table '{}' covers t in [{}, {}] s, but the motion was requested at "
          "t = {} s; extend the table or shorten the run",
          file, spline->t_first(), spline->t_last(), t);
    return (*spline)(t);
  };
}

}  // namespace hm::motion
