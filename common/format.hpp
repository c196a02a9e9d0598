#pragma once

/// @file
/// printf-style formatting into a std::string, for the sentences of reports and reasons, and the
/// number formats every module shares.

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

/// `value` as an output stream writes it with `precision` significant digits, which is printf's
/// "%.*g": by default 6 (20, 22.5, 1e-07), for messages and reports; 17 reads back bit for bit.
inline std::string StreamNumber(double value, int precision = 6) {
  std::ostringstream text;
  text.precision(precision);
  text << value;
  return text.str();
}

/// `value` with `decimals` digits after the point (printf's "%.*f"): 0.850, -12.0.
inline std::string FixedNumber(double value, int decimals) {
  return Format("%.*f", decimals, value);
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
