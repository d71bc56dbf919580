#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace hm {

/// Levenshtein edit distance (for "did you mean" suggestions).
std::size_t edit_distance(std::string_view a, std::string_view b);

/// The candidate closest to `word`, or "" when none is plausibly meant (distance > max(2,
/// |word|/3)).
std::string closest_match(std::string_view word, std::span<const std::string> candidates);

/// Joins strings with a separator.
std::string join(std::span<const std::string> parts, std::string_view separator);

}  // namespace hm
