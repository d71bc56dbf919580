// fsi-report's metrics (driver/report_stage.hpp) on curves with known answers, and its reader of
// digitised reference CSVs.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "../common/scratch.hpp"
#include "core/errors.hpp"
#include "driver/report_stage.hpp"

namespace hm::driver {
namespace {

const double nan = std::nan("");

// Run v = 2t, reference v = t sampled at 0, 0.5, 1: the peaks 2 and 1 at t = 1 (+100 %, Δt 0),
// RMS √((0 + 0.25 + 1)/3).
TEST(Report, MetricsOfKnownCurves) {
  Curve run, reference;
  for (int k = 0; k <= 100; ++k) {
    run.t.push_back(k / 100.0);
    run.v.push_back(2 * k / 100.0);
  }
  reference.t = {0.0, 0.5, 1.0};
  reference.v = {0.0, 0.5, 1.0};
  const CurveMetrics m = compare_curves(run, reference, nan, nan, "test");
  EXPECT_DOUBLE_EQ(m.peak, 2.0);
  EXPECT_DOUBLE_EQ(m.reference_peak, 1.0);
  EXPECT_DOUBLE_EQ(m.peak_error, 1.0);
  EXPECT_DOUBLE_EQ(m.peak_time_error, 0.0);
  EXPECT_NEAR(m.rms, std::sqrt(1.25 / 3), 1e-15);
  EXPECT_EQ(m.samples, 3);
  // A window cut to [0, 0.5]: the peaks at 0.5 (1 and 0.5), and a negative peak keeps its sign.
  const CurveMetrics w = compare_curves(run, reference, -1.0, 0.5, "test");
  EXPECT_DOUBLE_EQ(w.window_start, 0.0);
  EXPECT_DOUBLE_EQ(w.peak, 1.0);
  EXPECT_DOUBLE_EQ(w.reference_peak, 0.5);
  for (double& v : run.v) v = -v;
  EXPECT_DOUBLE_EQ(compare_curves(run, reference, nan, nan, "test").peak, -2.0);
  // No overlap: an error naming the context.
  Curve later{{2.0, 3.0}, {1.0, 1.0}};
  EXPECT_THROW(compare_curves(run, later, nan, nan, "test"), InputError);
}

// A probe dry for t < 0.4 (missing values, NaN) and v = 2t after: the peak and the RMS leave the
// missing samples out (the reference samples at 0 and 0.25 are counted as missing); a run with no
// value at all gives NaN metrics flagged without_fluid, not an error.
TEST(Report, MissingRunValuesAreLeftOutOfTheMetrics) {
  Curve run, reference;
  for (int k = 0; k <= 100; ++k) {
    run.t.push_back(k / 100.0);
    run.v.push_back(k < 40 ? nan : 2 * k / 100.0);
  }
  reference.t = {0.0, 0.25, 0.5, 1.0};
  reference.v = {0.0, 0.25, 0.5, 1.0};
  const CurveMetrics m = compare_curves(run, reference, nan, nan, "test");
  EXPECT_DOUBLE_EQ(m.peak, 2.0);
  EXPECT_EQ(m.samples, 4);
  EXPECT_EQ(m.missing, 2);
  EXPECT_NEAR(m.rms, std::sqrt((0.25 + 1.0) / 2), 1e-15);
  EXPECT_FALSE(m.without_fluid);
  for (double& v : run.v) v = nan;
  const CurveMetrics dry = compare_curves(run, reference, nan, nan, "test");
  EXPECT_TRUE(dry.without_fluid);
  EXPECT_TRUE(std::isnan(dry.peak));
  EXPECT_TRUE(std::isnan(dry.rms));
  EXPECT_DOUBLE_EQ(dry.reference_peak, 1.0);
}

TEST(Report, ReferenceCsvIsSortedScaledAndShifted) {
  const auto dir = test::fresh_dir("report_csv");
  {
    std::ofstream out(dir / "ref.csv");
    out << "time_s,value_mm,other\n0.2,20,0\n0.1,10,0\n\n0.3,30,0\n";
  }
  const Curve c = read_reference_csv(dir / "ref.csv", 0, 1, 1e-3, 2.0, 0.05);
  ASSERT_EQ(c.t.size(), 3u);
  EXPECT_DOUBLE_EQ(c.t[0], 0.25);  // 2·0.1 + 0.05
  EXPECT_DOUBLE_EQ(c.v[0], 0.010);
  EXPECT_DOUBLE_EQ(c.t[2], 0.65);
  {
    std::ofstream out(dir / "bad.csv");
    out << "t,v\n0.1,1\n0.2,oops\n";
  }
  try {
    read_reference_csv(dir / "bad.csv", 0, 1, 1.0, 1.0, 0.0);
    FAIL() << "a malformed row must be an error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_reference_csv(dir / "ref.csv", 0, 5, 1.0, 1.0, 0.0), InputError);
}

}  // namespace
}  // namespace hm::driver
