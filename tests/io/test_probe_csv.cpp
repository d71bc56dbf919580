// Probe CSV: header format, exact round trip, kill-safety (.partial), malformed-input messages.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "io/probe_csv.hpp"

namespace fs = std::filesystem;
using namespace hm::io;

namespace {

using hm::test::fresh_dir;
using hm::test::read_text;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

template <typename F>
std::string input_error_text(F&& f) {
  try {
    f();
  } catch (const hm::InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST(ProbeCsv, HeaderAndExactRoundTrip) {
  const fs::path dir = fresh_dir("probe_csv_round_trip");
  const fs::path path = dir / "probes.csv";
  const std::vector<std::string> columns = {"gauge1.eta [m]", "P1.p [Pa]", "surge.front [m]"};
  // Values that need 17 significant digits, tiny and huge magnitudes, negative zero.
  const std::vector<std::vector<double>> rows = {{0.1 + 0.2, 1.0 / 3.0, -0.0},
                                                 {1e-300, 2943.000000000001, 6.02214076e23},
                                                 {std::nextafter(1.0, 2.0), -1234.5, 0.59}};
  const std::vector<double> times = {0.0, 1e-3 / 3.0, 2.5};
  {
    ProbeCsvWriter writer(path, columns);
    for (std::size_t r = 0; r < rows.size(); ++r) writer.write_row(times[r], rows[r]);
    writer.finish();
  }
  EXPECT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(dir / "probes.csv.partial"));
  const std::string text = read_text(path);
  EXPECT_EQ(text.substr(0, text.find('\n')), "t [s],gauge1.eta [m],P1.p [Pa],surge.front [m]");
  const ProbeTable table = read_probe_csv(path);
  ASSERT_EQ(table.names.size(), 4u);
  EXPECT_EQ(table.names[0], "t [s]");
  EXPECT_EQ(table.names[2], "P1.p [Pa]");
  ASSERT_EQ(table.rows(), 3u);
  for (std::size_t r = 0; r < rows.size(); ++r) {
    EXPECT_EQ(table.columns[0][r], times[r]);
    for (std::size_t c = 0; c < columns.size(); ++c)
      EXPECT_EQ(table.column(columns[c])[r], rows[r][c]) << "row " << r << " column " << c;
  }
  EXPECT_TRUE(std::signbit(table.column("surge.front [m]")[0]));
  const auto m = input_error_text([&] { (void)table.column("gauge2.eta [m]"); });
  EXPECT_NE(m.find("no column 'gauge2.eta [m]'; it has: t [s], gauge1.eta [m]"), std::string::npos)
      << m;
}

TEST(ProbeCsv, RowsOfAnUnfinishedRunAreReadable) {
  const fs::path dir = fresh_dir("probe_csv_partial");
  const fs::path path = dir / "probes.csv";
  write_text(path, "stale result of an earlier run\n");
  {
    ProbeCsvWriter writer(path, {"gauge1.eta [m]"});
    EXPECT_FALSE(fs::exists(path));  // the stale file must not pass for this run's result
    writer.write_row(0.0, std::vector<double>{0.3});
    writer.write_row(0.01, std::vector<double>{0.31});
    // Not finished ("killed"): the rows are on disk already, flushed.
    const ProbeTable table = read_probe_csv(writer.partial_path());
    ASSERT_EQ(table.rows(), 2u);
    EXPECT_EQ(table.columns[1][1], 0.31);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::exists(dir / "probes.csv.partial"));
  // A row cut off mid-write (no line break at the end) is dropped; a complete one is kept.
  write_text(dir / "cut.csv", "t [s],g.eta [m]\n0,0.3\n0.01,0.3");
  EXPECT_EQ(read_probe_csv(dir / "cut.csv").rows(), 2u);
  write_text(dir / "cut.csv", "t [s],g.eta [m]\n0,0.3\n0.01,");
  EXPECT_EQ(read_probe_csv(dir / "cut.csv").rows(), 1u);
}

TEST(ProbeCsv, MalformedInputMessages) {
  const fs::path dir = fresh_dir("probe_csv_errors");
  auto read_error = [&](const std::string& text) {
    write_text(dir / "bad.csv", text);
    return input_error_text([&] { read_probe_csv(dir / "bad.csv"); });
  };
  auto m = read_error("t [s],g1.eta [m],P1.p [Pa]\n0,0.3,100\n0.01,0.3x,101\n");
  EXPECT_NE(m.find("bad.csv"), std::string::npos) << m;
  EXPECT_NE(m.find("line 3, column 2 ('g1.eta [m]'): '0.3x' is not a number"), std::string::npos)
      << m;
  m = read_error("t [s],g1.eta [m],P1.p [Pa]\n0,0.3,100\n0.01,0.3\n");
  EXPECT_NE(m.find("line 3 has 2 fields, the header has 3 columns"), std::string::npos) << m;
  m = read_error("time,g1.eta [m]\n0,0.3\n");
  EXPECT_NE(m.find("line 1, column 1: 'time' should be 't [s]'"), std::string::npos) << m;
  m = read_error("t [s],g1.eta\n0,0.3\n");
  EXPECT_NE(m.find("line 1, column 2: 'g1.eta' is not of the form '<probe>.<quantity> [unit]'"),
            std::string::npos)
      << m;
  m = read_error("");
  EXPECT_NE(m.find("bad.csv' is empty"), std::string::npos) << m;
  m = input_error_text([&] { read_probe_csv(dir / "missing.csv"); });
  EXPECT_NE(m.find("cannot open the probe file"), std::string::npos) << m;
  EXPECT_NE(m.find("missing.csv"), std::string::npos) << m;
  // The writer refuses column names that would break the format.
  m = input_error_text([&] { ProbeCsvWriter(dir / "w.csv", {"g1.eta [m]", "P1,p [Pa]"}); });
  EXPECT_NE(m.find("column 3 'P1,p [Pa]' is not of the form '<probe>.<quantity> [unit]'"),
            std::string::npos)
      << m;
  EXPECT_FALSE(is_probe_column_name("eta [m]"));
  EXPECT_FALSE(is_probe_column_name("g1.eta"));
  EXPECT_FALSE(is_probe_column_name("g1.eta []"));
  EXPECT_TRUE(is_probe_column_name("wall.Fx [N/m]"));
}

}  // namespace
