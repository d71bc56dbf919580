#pragma once
// Prescribed motion as a time table read from CSV, interpolated by cubic splines.
//
// File format: comma-separated, exactly one header line, then one row per time.
//   first column   `t [s]`, strictly increasing, at least 4 rows
//   other columns  any of `x [m]`, `y [m]`, `z [m]` (displacement of the body along the global
//                  axes) and `theta [rad]` or `theta [deg]` (rotation angle about the motion's
//                  axis), each at most once, in any order.
// Blank lines are skipped; fields may carry surrounding spaces.
//
// Interpolation (CHOICE): a not-a-knot cubic spline through each column. Position, velocity and
// acceleration are the spline and its exact first and second derivatives, so they are mutually
// consistent (the velocity integrates to the position) and the acceleration is continuous
// (piecewise linear). For smooth data sampled with spacing h the errors are O(h⁴) in position,
// O(h³) in velocity and O(h²) in acceleration. Measured (tests/motion) for sway 0.06 m at
// T = 1.94 s plus roll 4° at 0.61 Hz, vertices up to 1.7 m from the pivot, at 40 samples per
// period: position 2.9e-6 m, velocity 3.8e-4 m/s, acceleration 3.1e-2 m/s² (≈ 1 % of the peak
// 2.6 m/s²; 0.3 % at 80 samples). Sample the table finely when wall accelerations matter (they
// enter the wall pressure condition). Evaluating outside
// [t_first, t_last] is an InputError: the table does not cover the requested time.
#include <filesystem>
#include <string>
#include <vector>

#include "motion/laws.hpp"

namespace hm::motion {

/// Interpolating cubic spline with not-a-knot end conditions (needs ≥ 4 strictly increasing
/// abscissae).
class CubicSpline {
 public:
  CubicSpline(std::vector<double> t, std::vector<double> y);
  Jet operator()(double t) const;  ///< t must lie in [t.front(), t.back()]
  double t_first() const { return t_.front(); }
  double t_last() const { return t_.back(); }

 private:
  std::vector<double> t_, y_, m_;  // m_ = second derivatives at the knots
};

struct TimeTable {
  std::string file;                         ///< as given, for messages
  std::vector<double> time;                 ///< s
  std::vector<std::string> columns;         ///< header names after `t [s]`
  std::vector<std::vector<double>> values;  ///< values[column][row], units of the header
};

/// Reads and validates a table; InputError naming file, line and what was expected.
TimeTable read_time_table(const std::filesystem::path& file);
/// The same with other accepted columns after `t [s]` (e.g. {"factor [1]"} for a load history).
TimeTable read_time_table(const std::filesystem::path& file,
                          const std::vector<std::string>& accepted);

/// Spline law of column `column` of `table`, scaled by `scale` (e.g. deg → rad). Evaluation
/// outside the table's time range throws InputError naming the file and the range.
ScalarLaw table_law(const TimeTable& table, std::size_t column, double scale = 1.0);

}  // namespace hm::motion
