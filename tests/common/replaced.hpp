#pragma once
// Scene and study texts with one piece swapped: the bad-input tests build their cases with it.
#include <gtest/gtest.h>

#include <string>

namespace hm::test {

/// `text` with its first `from` replaced by `to`; a test failure when `from` is not in it.
inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

}  // namespace hm::test
