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

/// `text` without leading and trailing blanks, tabs and CRs.
std::string_view trimmed(std::string_view text);

/// The fields of `text` between `separator`s, each trimmed ("a, b" → {"a", "b"}; "" → {""}).
std::vector<std::string> split_fields(std::string_view text, char separator);

/// The comma-separated fields of one CSV line, each trimmed of blanks, tabs and a trailing CR.
inline std::vector<std::string> split_csv_fields(std::string_view line) {
  return split_fields(line, ',');
}

/// Parses a number that fills `text` exactly (no blanks, nothing after it); false otherwise.
/// "inf" and "nan" parse: callers that need a finite value check it.
bool parse_number(std::string_view text, double& value);

}  // namespace hm
