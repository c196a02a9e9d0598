#include "request/option.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <sstream>

#include "common/format.hpp"
#include "common/orientation_list.hpp"
#include "common/text_input.hpp"

namespace graspsynth::request {
namespace {

// "[0, 1)", "(0, 0.02]", ">= 0": the range of a number or an integer, for messages and help.
std::string RangeText(const OptionInfo& info) {
  const bool low = std::isfinite(info.lo), high = std::isfinite(info.hi);
  if (low && high) {
    return std::string(info.lo_open ? "(" : "[") + ShortestNumber(info.lo) + ", " +
           ShortestNumber(info.hi) + (info.hi_open ? ")" : "]");
  }
  if (low) return (info.lo_open ? "> " : ">= ") + ShortestNumber(info.lo);
  if (high) return (info.hi_open ? "< " : "<= ") + ShortestNumber(info.hi);
  return "";
}

bool InRange(const OptionInfo& info, double v) {
  if (!std::isfinite(v)) return false;
  if (info.lo_open ? !(v > info.lo) : !(v >= info.lo)) return false;
  if (info.hi_open ? !(v < info.hi) : !(v <= info.hi)) return false;
  return true;
}

std::string Joined(const std::vector<std::string>& texts, const char* separator) {
  std::string out;
  for (size_t i = 0; i < texts.size(); ++i) out += (i ? separator : "") + texts[i];
  return out;
}

std::string CheckChoice(const OptionInfo& info, const std::string& text) {
  if (info.choices.empty() ||
      std::find(info.choices.begin(), info.choices.end(), text) != info.choices.end()) {
    return "";
  }
  return "'" + text + "' is not one of " + Joined(info.choices, ", ");
}

std::string CheckNumbers(const OptionInfo& info, const std::vector<double>& v) {
  for (double x : v) {
    if (!std::isfinite(x)) return "needs finite numbers";
  }
  if (info.kind == OptionKind::kNumberPair) {
    if (v.size() != 2) return "needs two numbers, MIN MAX";
    if (!(v[0] > 0.0 && v[0] <= v[1])) {
      return "needs 0 < MIN <= MAX (got " + ShowValue(info, v) + ")";
    }
    return "";
  }
  if (!v.empty() && static_cast<int>(v.size()) != info.count) {
    return "needs " + info.Placeholder() + " (" + std::to_string(info.count) + " numbers), got " +
           std::to_string(v.size());
  }
  return "";
}

// the integer of a whole text (surrounding blanks allowed), or nothing.
template <class T>
std::optional<T> IntegerOf(std::string_view text) {
  text = TrimBlanks(text);
  T v{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return v;
}

// the numbers of a command-line text "a,b,c" (commas; a pair may also be "a b").
std::vector<double> NumbersOf(const std::string& text, const std::string& where) {
  std::vector<double> v;
  std::string item;
  std::stringstream s(text);
  while (std::getline(s, item, ',')) {
    const std::optional<double> x = ParseFiniteDouble(item);
    if (!x) throw InputError(where + ": '" + item + "' in '" + text + "' is not a finite number");
    v.push_back(*x);
  }
  if (!text.empty() && text.back() == ',') {
    throw InputError(where + ": '" + text + "' ends with a comma");
  }
  return v;
}

std::vector<std::string> TextsOf(const std::string& text) {
  std::vector<std::string> v;
  std::string item;
  std::stringstream s(text);
  while (std::getline(s, item, ',')) v.push_back(item);
  return v;
}

// Levenshtein distance, for the nearest option name.
size_t EditDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

}  // namespace

bool OptionInfo::Negated(const Value& default_value) const {
  return kind == OptionKind::kBool && !on_off && std::holds_alternative<bool>(default_value) &&
         std::get<bool>(default_value);
}

std::string OptionInfo::Flag(const Value& default_value) const {
  std::string flag = name;
  std::replace(flag.begin(), flag.end(), '_', '-');
  return (Negated(default_value) ? "--no-" : "--") + flag;
}

std::string OptionInfo::Placeholder() const {
  if (!placeholder.empty()) return placeholder;
  switch (kind) {
    case OptionKind::kBool:
      return on_off ? "on|off" : "";
    case OptionKind::kInt:
    case OptionKind::kUnsigned:
      return "INT";
    case OptionKind::kNumber:
      return "NUMBER";
    case OptionKind::kText:
      return choices.empty() ? "TEXT" : Joined(choices, "|");
    case OptionKind::kTextList:
      return "A,B,...";
    case OptionKind::kNumbers:
      return "N1,...,N" + std::to_string(count);
    case OptionKind::kNumberPair:
      return "MIN MAX";
  }
  return "";
}

std::string CheckValue(const OptionInfo& info, const Value& value) {
  if (std::holds_alternative<std::monostate>(value)) return info.optional ? "" : "needs a value";
  switch (info.kind) {
    case OptionKind::kBool:
      return std::holds_alternative<bool>(value) ? "" : "needs true or false";
    case OptionKind::kInt: {
      if (!std::holds_alternative<int64_t>(value)) return "needs an integer";
      const int64_t v = std::get<int64_t>(value);
      if (v < INT_MIN || v > INT_MAX) return "is too large (got " + std::to_string(v) + ")";
      if (!InRange(info, static_cast<double>(v))) {
        return "must be " + RangeText(info) + " (got " + std::to_string(v) + ")";
      }
      return "";
    }
    case OptionKind::kUnsigned:
      return std::holds_alternative<uint64_t>(value) ? "" : "needs an integer >= 0";
    case OptionKind::kNumber: {
      if (!std::holds_alternative<double>(value)) return "needs a number";
      const double v = std::get<double>(value);
      if (!InRange(info, v)) {
        const std::string range = RangeText(info);
        return (range.empty() ? std::string("must be finite") : "must be " + range) + " (got " +
               ShortestNumber(v) + ")";
      }
      return "";
    }
    case OptionKind::kText:
      if (!std::holds_alternative<std::string>(value)) return "needs a text";
      return CheckChoice(info, std::get<std::string>(value));
    case OptionKind::kTextList: {
      if (!std::holds_alternative<std::vector<std::string>>(value)) return "needs a list of texts";
      const auto& texts = std::get<std::vector<std::string>>(value);
      if (texts.empty()) return "needs at least one";
      for (const std::string& t : texts) {
        if (std::string why = CheckChoice(info, t); !why.empty()) return why;
      }
      return "";
    }
    case OptionKind::kNumbers:
    case OptionKind::kNumberPair:
      if (!std::holds_alternative<std::vector<double>>(value)) return "needs numbers";
      return CheckNumbers(info, std::get<std::vector<double>>(value));
  }
  return "";
}

std::string ShowValue(const OptionInfo& info, const Value& value) {
  return std::visit(
      [&](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return "";
        } else if constexpr (std::is_same_v<T, bool>) {
          return info.on_off ? (v ? "on" : "off") : (v ? "true" : "false");
        } else if constexpr (std::is_same_v<T, int64_t> || std::is_same_v<T, uint64_t>) {
          return std::to_string(v);
        } else if constexpr (std::is_same_v<T, double>) {
          return ShortestNumber(v);
        } else if constexpr (std::is_same_v<T, std::string>) {
          return v;
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          return Joined(v, ",");
        } else {
          std::vector<std::string> texts;
          for (double x : v) texts.push_back(ShortestNumber(x));
          return Joined(texts, info.kind == OptionKind::kNumberPair ? " " : ",");
        }
      },
      value);
}

Value ParseText(const OptionInfo& info, const std::string& text, const std::string& where) {
  Value value;
  switch (info.kind) {
    case OptionKind::kBool:
      if (text != "on" && text != "off" && text != "true" && text != "false") {
        throw InputError(where + ": '" + text + "' is neither on nor off");
      }
      value = text == "on" || text == "true";
      break;
    case OptionKind::kInt: {
      const std::optional<int64_t> v = IntegerOf<int64_t>(text);
      if (!v) throw InputError(where + ": '" + text + "' is not an integer");
      value = *v;
      break;
    }
    case OptionKind::kUnsigned: {
      const std::optional<uint64_t> v = IntegerOf<uint64_t>(text);
      if (!v) throw InputError(where + ": '" + text + "' is not an integer >= 0");
      value = *v;
      break;
    }
    case OptionKind::kNumber: {
      const std::optional<double> v = ParseFiniteDouble(text);
      if (!v) throw InputError(where + ": '" + text + "' is not a finite number");
      value = *v;
      break;
    }
    case OptionKind::kText:
      value = text;
      break;
    case OptionKind::kTextList:
      value = TextsOf(text);
      break;
    case OptionKind::kNumbers:
    case OptionKind::kNumberPair: {
      std::string commas = text;
      if (info.kind == OptionKind::kNumberPair)
        std::replace(commas.begin(), commas.end(), ' ', ',');
      value = NumbersOf(commas, where);
      break;
    }
  }
  if (const std::string why = CheckValue(info, value); !why.empty()) {
    const bool list = info.kind == OptionKind::kNumbers || info.kind == OptionKind::kNumberPair;
    throw InputError(where + ": " + (list ? "'" + text + "' " : std::string()) + why);
  }
  return value;
}

Value ValueFromJson(const OptionInfo& info, const JsonReader& field) {
  if (info.optional && field.IsNull()) return std::monostate{};
  switch (info.kind) {
    case OptionKind::kBool:
      return field.AsBool();
    case OptionKind::kInt:
      // an int; its range is the option's check, with the same words as a flag's.
      return field.AsInteger(INT_MIN, INT_MAX);
    case OptionKind::kUnsigned:
      return field.AsUnsigned();
    case OptionKind::kNumber:
      return field.AsNumber();
    case OptionKind::kText:
      if (info.number_list && field.IsArray()) {
        std::vector<std::string> texts;
        for (const JsonReader& x : field.AsArray()) texts.push_back(ShortestNumber(x.AsNumber()));
        return Joined(texts, ",");
      }
      return field.AsString();
    case OptionKind::kTextList: {
      if (field.IsString()) return TextsOf(field.AsString());
      std::vector<std::string> texts;
      for (const JsonReader& x : field.AsArray()) texts.push_back(x.AsString());
      return texts;
    }
    case OptionKind::kNumbers:
    case OptionKind::kNumberPair: {
      std::vector<double> v;
      for (const JsonReader& x : field.AsArray()) v.push_back(x.AsNumber());
      return v;
    }
  }
  return Value();
}

std::function<void(const Value&, const std::string&)> NumberListCheck(const char* unit) {
  return [unit](const Value& value, const std::string& where) {
    const auto* text = std::get_if<std::string>(&value);  // none (an optional list) passes
    if (text && !text->empty()) ParseNumberList(*text, where, unit);
  };
}

std::string NearestName(const std::vector<std::string>& names, std::string_view name) {
  std::string best;
  size_t best_distance = name.size() / 3 + 1;
  for (const std::string& n : names) {
    const size_t d = EditDistance(n, name);
    if (d < best_distance) {
      best = n;
      best_distance = d;
    }
  }
  return best;
}

namespace detail {

std::vector<std::pair<size_t, JsonReader>> ConfigFields(const std::filesystem::path& file,
                                                        const std::vector<std::string>& names) {
  const JsonReader root = JsonReader::Load(file);
  root.AsObject();
  std::vector<std::pair<size_t, JsonReader>> fields;
  for (const std::string& key : root.Keys()) {
    if (key == "format") {
      root.ExpectString("format", kOptionsFormat);
      continue;
    }
    const auto it = std::find(names.begin(), names.end(), key);
    if (it == names.end()) {
      const std::string nearest = NearestName(names, key);
      throw InputError(root.source() + ": field '" + key + "' is not an option of this command" +
                       (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)") +
                       "; its options: " + Joined(names, ", "));
    }
    fields.emplace_back(static_cast<size_t>(it - names.begin()), root.Field(key));
  }
  return fields;
}

}  // namespace detail

}  // namespace graspsynth::request
