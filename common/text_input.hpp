#pragma once

/// @file
/// Strict parsing of numbers from text (command input lines, CSV fields). Nothing is guessed:
/// a field that is not a complete, finite decimal number is an error naming the field.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace graspsynth {

/// Parses one number. Returns std::nullopt unless the whole of `text` (surrounding blanks
/// allowed) is a finite decimal number.
std::optional<double> ParseFiniteDouble(std::string_view text);

/// Splits `line` on blanks and commas and parses every field with ParseFiniteDouble.
/// On success returns the numbers; otherwise returns std::nullopt and, when `why` is given,
/// stores which field (1-based) and value were wrong, or how many fields were found when
/// `expected_count` (if non-zero) does not match.
std::optional<std::vector<double>> ParseNumberList(std::string_view line, size_t expected_count,
                                                   std::string* why);

/// Splits `line` on the single character `separator`, keeping empty fields.
std::vector<std::string_view> SplitFields(std::string_view line, char separator);

/// `text` without leading and trailing blanks (spaces, tabs, carriage returns).
std::string_view TrimBlanks(std::string_view text);

}  // namespace graspsynth
