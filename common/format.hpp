#pragma once

/// @file
/// printf-style formatting into a std::string, for the sentences of reports and reasons.

#include <charconv>
#include <cstdio>
#include <sstream>
#include <string>

namespace graspsynth {

/// printf into a std::string of whatever length the text needs. The arguments must match the
/// conversions (`%f` takes a double, `%d` an int): the compiler does not check a format that is
/// not a literal at the call.
template <typename... Args>
std::string Format(const char* format, Args... args) {
  const int n = std::snprintf(nullptr, 0, format, args...);
  if (n <= 0) return std::string();
  std::string text(static_cast<size_t>(n), '\0');
  std::snprintf(text.data(), text.size() + 1, format, args...);
  return text;
}

/// `value` as an output stream writes it by default (6 significant digits: 62.5, 1e-07), for the
/// numbers of messages.
inline std::string StreamNumber(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

/// The shortest text that reads back to exactly `value` (std::to_chars): 0.85, not
/// 0.84999999999999998.
inline std::string ShortestNumber(double value) {
  char buffer[64];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  if (ec != std::errc()) return std::to_string(value);  // cannot happen with 64 characters
  return std::string(buffer, end);
}

}  // namespace graspsynth
