#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "core/progress.hpp"
#include "core/text.hpp"

TEST(Text, EditDistanceAndSuggestions) {
  EXPECT_EQ(hm::edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(hm::edit_distance("", "abc"), 3u);
  const std::vector<std::string> keys{"youngs_modulus", "poisson_ratio", "density"};
  EXPECT_EQ(hm::closest_match("youngs_modulos", keys), "youngs_modulus");
  EXPECT_EQ(hm::closest_match("densty", keys), "density");
  EXPECT_EQ(hm::closest_match("completely_different", keys), "");
}

TEST(Errors, ExitCodesAndAssertions) {
  EXPECT_EQ(hm::InputError("x").code(), hm::ExitCode::invalid_input);
  EXPECT_EQ(hm::NumericalError("x").code(), hm::ExitCode::numerical_failure);
  EXPECT_EQ(hm::UsageError("x").code(), hm::ExitCode::usage);
  try {
    HM_ASSERT(1 + 1 == 3, "arithmetic {}", "broke");
    FAIL() << "assertions must be on in test builds";
  } catch (const hm::InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("arithmetic broke"), std::string::npos);
  }
}

TEST(Progress, PlainLinesWhenNotATerminal) {
  // stderr of a test run by ctest is not a terminal: plain lines, at most one per interval.
  std::fflush(stderr);
  const std::string path = testing::TempDir() + "progress.txt";
  FILE* saved = fdopen(dup(fileno(stderr)), "w");
  ASSERT_TRUE(std::freopen(path.c_str(), "w", stderr));
  {
    hm::Progress::plain_interval_s = 0.0;
    hm::Progress progress("simulate", 2.0, "s");
    progress.update(1.0);
    progress.finish();
    hm::Progress::plain_interval_s = 10.0;
  }
  std::fflush(stderr);
  dup2(fileno(saved), fileno(stderr));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("simulate: 50% 1/2 s"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("simulate: 100% 2/2 s"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("ETA"), std::string::npos) << text.str();
  EXPECT_EQ(text.str().find('\r'), std::string::npos) << "no carriage returns in logs";
}
