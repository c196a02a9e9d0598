#include "common/text_input.hpp"

#include <charconv>
#include <cmath>

namespace graspsynth {

std::string_view TrimBlanks(std::string_view text) {
  constexpr std::string_view kBlanks = " \t\r\n";
  const size_t first = text.find_first_not_of(kBlanks);
  if (first == std::string_view::npos) return {};
  const size_t last = text.find_last_not_of(kBlanks);
  return text.substr(first, last - first + 1);
}

std::optional<double> ParseFiniteDouble(std::string_view text) {
  text = TrimBlanks(text);
  if (text.empty()) return std::nullopt;
  // from_chars rejects a leading '+', which people do write.
  if (text.front() == '+') text.remove_prefix(1);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    return std::nullopt;
  }
  return value;
}

std::vector<std::string_view> SplitFields(std::string_view line, char separator) {
  std::vector<std::string_view> fields;
  size_t start = 0;
  while (true) {
    const size_t end = line.find(separator, start);
    if (end == std::string_view::npos) {
      fields.push_back(line.substr(start));
      return fields;
    }
    fields.push_back(line.substr(start, end - start));
    start = end + 1;
  }
}

std::optional<std::vector<double>> ParseNumberList(std::string_view line, size_t expected_count,
                                                   std::string* why) {
  std::vector<double> values;
  size_t pos = 0;
  constexpr std::string_view kSeparators = " \t\r\n,";
  while (true) {
    pos = line.find_first_not_of(kSeparators, pos);
    if (pos == std::string_view::npos) break;
    const size_t end = std::min(line.find_first_of(kSeparators, pos), line.size());
    const std::string_view field = line.substr(pos, end - pos);
    const std::optional<double> value = ParseFiniteDouble(field);
    if (!value) {
      if (why) {
        *why = "field " + std::to_string(values.size() + 1) + " is not a finite number: '" +
               std::string(field) + "'";
      }
      return std::nullopt;
    }
    values.push_back(*value);
    pos = end;
  }
  if (expected_count != 0 && values.size() != expected_count) {
    if (why) {
      *why = "expected " + std::to_string(expected_count) + " numbers, found " +
             std::to_string(values.size());
    }
    return std::nullopt;
  }
  return values;
}

}  // namespace graspsynth
