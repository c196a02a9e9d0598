#pragma once

/// @file
/// One description of each option of a request, the work of a command of `graspsynth` and of
/// the Python function that does the same: its name, kind, range, default and help. Every front
/// end is made from it: the command's flags (apps/request_flags.hpp), the Python function's
/// keyword arguments (python/request_bindings.cpp, graspsynth/__init__.py) and a JSON file of
/// options (`--config FILE`, ApplyConfig). The checks are made here, once, for every front end:
/// a value out of its range or not one of its choices is refused with an InputError that names
/// the option as the front end spells it ("--perturb", "perturb", "run.json: field 'perturb'").
///
/// A request type (say SynthesizeRequest, request/synthesize_request.hpp) is a plain struct
/// whose defaults are the options' defaults; its OptionList says how each option reads and
/// writes it, through nested library options where they exist (the request holds a
/// PhysicsGateOptions, not copies of its fields).

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "common/errors.hpp"
#include "common/json_reader.hpp"

namespace graspsynth::request {

/// `format` of a file of options (`--config FILE`); the tag is optional in the file.
inline constexpr std::string_view kOptionsFormat = "graspsynth-options/1";

/// What an option holds, and how each front end writes it.
enum class OptionKind {
  kBool,        ///< flag --NAME (default false) or --no-NAME (default true); Python bool
  kInt,         ///< an integer in [lo, hi] (and in the range of an int)
  kUnsigned,    ///< an integer >= 0 (seeds)
  kNumber,      ///< a finite number in its range
  kText,        ///< a text, one of `choices` when it has them
  kTextList,    ///< texts: command line "a,b"; Python and JSON a list of texts
  kNumbers,     ///< `count` finite numbers, or none: command line "x,y"; Python and JSON a list
  kNumberPair,  ///< two numbers MIN MAX (0 < MIN <= MAX): command line two values
};

/// The value of an option, by kind: bool; int64_t (kInt); uint64_t (kUnsigned); double
/// (kNumber); std::string (kText); texts (kTextList); numbers (kNumbers, kNumberPair); and
/// std::monostate, none, for an optional option (OptionInfo::optional) left unset.
using Value = std::variant<bool, int64_t, uint64_t, double, std::string, std::vector<std::string>,
                           std::vector<double>, std::monostate>;

/// What the front ends show of an option and check of its values.
struct OptionInfo {
  std::string name;  ///< snake_case: the Python keyword and the config key; the flag --kebab-case
  OptionKind kind = OptionKind::kBool;
  std::string help;                       ///< one sentence or two, with the unit
  double lo = -INFINITY, hi = INFINITY;   ///< kInt, kNumber: the range
  bool lo_open = false, hi_open = false;  ///< kNumber: the range excludes lo, hi
  std::vector<std::string> choices;       ///< kText, kTextList: the allowed texts (empty: any)
  int count = 0;                          ///< kNumbers: how many numbers
  bool required = false;                  ///< no default: the front end must give it
  /// kInt, kUnsigned, kNumber: may be none (std::monostate): the command line leaves the flag
  /// out, Python gives None, JSON null; its default is none (say in `help` what none means).
  bool optional = false;
  bool on_off = false;       ///< kBool: the command line spells it --NAME on|off, not a flag
  bool number_list = false;  ///< kText: also a list of numbers (Python, JSON), written "a,b"
  std::string group;         ///< the help's heading for it (empty: the command's options)
  std::string placeholder;   ///< what the help shows for its value ("X,Y"); empty: by kind

  /// The placeholder, or the kind's: NUMBER, INT, TEXT, a|b|c, on|off, MIN MAX, N1,...,N7.
  std::string Placeholder() const;

  /// The command-line flag: "--" and the name with '-' for '_' ("--min-robustness"), or
  /// "--no-..." for a bool that is true by default (given `default_value`).
  std::string Flag(const Value& default_value) const;
  /// Whether the flag is "--no-NAME": a bool switch (not on|off) that is true by default.
  bool Negated(const Value& default_value) const;
};

/// Why `value` is not a value of `info` (its kind, range or choices), or "" when it is.
std::string CheckValue(const OptionInfo& info, const Value& value);

/// `value` as the help and the Python signature show it: "20", "0.8", "on", "interp",
/// "nearest,interp", "0.5 2", "" for no numbers.
std::string ShowValue(const OptionInfo& info, const Value& value);

/// The value of a command-line text for `info` (never none) (a number, a text, "a,b" lists,
/// "on"/"off"). Throws InputError "<where>: <why>" when it does not parse or is out of range.
Value ParseText(const OptionInfo& info, const std::string& text, const std::string& where);

/// The value of a JSON field for `info`; throws InputError naming the file and the field.
Value ValueFromJson(const OptionInfo& info, const JsonReader& field);

/// One option of request type R: what it is, and how it reads and writes R.
template <class R>
struct Option {
  OptionInfo info;
  std::function<Value(const R&)> get;
  std::function<void(R&, const Value&)> set;
  /// A further check of a value that passed CheckValue: throws InputError naming `where`.
  std::function<void(const Value& value, const std::string& where)> check;
};

/// The options of a request type, in the order the front ends list them.
template <class R>
using OptionList = std::vector<Option<R>>;

/// Sets `option` of `request` to `value` after checking it; throws InputError "<where>: <why>"
/// when it is not a value of the option.
template <class R>
void Apply(const Option<R>& option, const Value& value, const std::string& where, R* request) {
  if (const std::string why = CheckValue(option.info, value); !why.empty()) {
    throw InputError(where + ": " + why);
  }
  if (option.check) option.check(value, where);
  option.set(*request, value);
}

/// A check (Option::check) that a text is empty or a list of numbers and ranges FROM:TO:STEP
/// of `unit` (common/orientation_list.hpp), for an option with OptionInfo::number_list.
std::function<void(const Value& value, const std::string& where)> NumberListCheck(const char* unit);

/// The option named `name`, or nullptr.
template <class R>
const Option<R>* FindOption(const OptionList<R>& options, std::string_view name) {
  for (const Option<R>& o : options) {
    if (o.info.name == name) return &o;
  }
  return nullptr;
}

/// The name of `names` nearest to a mistyped `name` (by edit distance, at most a third of its
/// length), or "" when none is that near.
std::string NearestName(const std::vector<std::string>& names, std::string_view name);

namespace detail {
/// The fields of the JSON object of options in `file`, each with the option it sets (an index
/// in `names`); checks the format tag when the file has one. Throws InputError as ApplyConfig
/// says.
std::vector<std::pair<size_t, JsonReader>> ConfigFields(const std::filesystem::path& file,
                                                        const std::vector<std::string>& names);
}  // namespace detail

/// Reads a JSON object of options (`--config FILE`: {"perturb": 5, "method": "line"}, and
/// optionally "format": "graspsynth-options/1") into `request`, over what it holds. Throws
/// InputError naming the file and the field for a file that cannot be read, a key that is not
/// an option (with the nearest option's name) or a value that is not one of the option's.
/// Returns the indices in `options` of the options the file set.
template <class R>
std::vector<size_t> ApplyConfig(const OptionList<R>& options, const std::filesystem::path& file,
                                R* request) {
  std::vector<std::string> names;
  for (const Option<R>& o : options) names.push_back(o.info.name);
  std::vector<size_t> set;
  for (const auto& [k, field] : detail::ConfigFields(file, names)) {
    Apply(options[k], ValueFromJson(options[k].info, field),
          field.source() + ": field '" + field.path() + "'", request);
    set.push_back(k);
  }
  return set;
}

/// The description of an option `name` of `kind` with `help`; the rest at their defaults.
inline OptionInfo MakeInfo(std::string name, OptionKind kind, std::string help) {
  OptionInfo info;
  info.name = std::move(name);
  info.kind = kind;
  info.help = std::move(help);
  return info;
}

/// `info` with the range from `lo` to `hi` (kInt, kNumber); `lo_open`, `hi_open` leave the ends
/// out.
inline OptionInfo WithRange(OptionInfo info, double lo, double hi = INFINITY, bool lo_open = false,
                            bool hi_open = false) {
  info.lo = lo;
  info.hi = hi;
  info.lo_open = lo_open;
  info.hi_open = hi_open;
  return info;
}

/// `info` with the allowed texts `choices` (kText, kTextList).
inline OptionInfo WithChoices(OptionInfo info, std::vector<std::string> choices) {
  info.choices = std::move(choices);
  return info;
}

/// The description of the option threads, worker threads in [0, 1024] (0: all cores), with
/// `help`.
inline OptionInfo ThreadsInfo(std::string help) {
  return WithRange(MakeInfo("threads", OptionKind::kInt, std::move(help)), 0, 1024);
}

/// Makes an option that reads and writes the field `ref` returns, a lambda
/// `[](R& r) -> T& { return r.gate.robustness.seed; }` (through nested options where they are); T
/// is bool, int, uint64_t, double, std::string or std::vector<std::string>.
template <class R, class F>
Option<R> FieldOption(OptionInfo info, F ref) {
  using T = std::remove_reference_t<std::invoke_result_t<F, R&>>;
  Option<R> o;
  o.info = std::move(info);
  o.get = [ref](const R& r) -> Value {
    const T& v = ref(const_cast<R&>(r));
    if constexpr (std::is_same_v<T, int>) {
      return static_cast<int64_t>(v);
    } else {
      return v;
    }
  };
  o.set = [ref](R& r, const Value& v) {
    if constexpr (std::is_same_v<T, int>) {
      ref(r) = static_cast<int>(std::get<int64_t>(v));
    } else {
      ref(r) = std::get<T>(v);
    }
  };
  return o;
}

/// Makes an optional option (OptionInfo::optional) that reads and writes the std::optional<T>
/// field `ref` returns; T is int, uint64_t or double; none is std::monostate.
template <class R, class F>
Option<R> OptionalFieldOption(OptionInfo info, F ref) {
  using T = typename std::remove_reference_t<std::invoke_result_t<F, R&>>::value_type;
  using V = std::conditional_t<std::is_same_v<T, int>, int64_t, T>;
  info.optional = true;
  Option<R> o;
  o.info = std::move(info);
  o.get = [ref](const R& r) -> Value {
    const std::optional<T>& v = ref(const_cast<R&>(r));
    if (!v) return std::monostate{};
    return static_cast<V>(*v);
  };
  o.set = [ref](R& r, const Value& v) {
    if (std::holds_alternative<std::monostate>(v)) {
      ref(r).reset();
    } else {
      ref(r) = static_cast<T>(std::get<V>(v));
    }
  };
  return o;
}

/// Makes a kText option of numbers and ranges FROM:TO:STEP of `unit` (OptionInfo::number_list,
/// checked by NumberListCheck) named `name` with `help`, that reads and writes the text field
/// `ref` returns (orientations, x, y): a std::string ("" the default), or a
/// std::optional<std::string> (none the default, an empty text refused).
template <class R, class F>
Option<R> NumberListOption(std::string name, const char* unit, std::string help, F ref) {
  OptionInfo info = MakeInfo(std::move(name), OptionKind::kText, std::move(help));
  info.number_list = true;
  using T = std::remove_reference_t<std::invoke_result_t<F, R&>>;
  Option<R> o;
  if constexpr (std::is_same_v<T, std::string>) {
    o = FieldOption<R>(std::move(info), ref);
  } else {
    o = OptionalFieldOption<R>(std::move(info), ref);
  }
  o.check = NumberListCheck(unit);
  return o;
}

/// Appends the options x (with `x_help`) and y, object positions on the table in metres
/// (NumberListOption), reading and writing the texts `x_ref` and `y_ref` return.
template <class R, class FX, class FY>
void AppendPositionListOptions(std::string x_help, FX x_ref, FY y_ref, OptionList<R>* list) {
  list->push_back(NumberListOption<R>("x", "metres", std::move(x_help), x_ref));
  list->push_back(NumberListOption<R>(
      "y", "metres", "Object positions: y of the object centre, m (see x)", y_ref));
}

/// Makes an option of N numbers (OptionKind::kNumbers, `info.count` set to N) held as an
/// optional fixed-size vector, the field `ref` returns (`[](R& r) -> std::optional<V>& { return
/// r.at; }`): no numbers is none.
template <class R, int N, class F>
Option<R> OptionalVectorOption(OptionInfo info, F ref) {
  info.count = N;
  Option<R> o;
  o.info = std::move(info);
  o.get = [ref](const R& r) -> Value {
    const auto& v = ref(const_cast<R&>(r));
    return v ? std::vector<double>(v->data(), v->data() + N) : std::vector<double>();
  };
  o.set = [ref](R& r, const Value& value) {
    const auto& v = std::get<std::vector<double>>(value);
    auto& field = ref(r);
    if (v.empty()) {
      field.reset();
    } else {
      field.emplace();
      for (int i = 0; i < N; ++i) (*field)[i] = v[static_cast<size_t>(i)];
    }
  };
  return o;
}

/// Makes the option at, X,Y of the object centre on the table (world, m) or none, with `help`,
/// reading and writing the std::optional<Eigen::Vector2d> field `ref` returns.
template <class R, class F>
Option<R> AtOption(std::string help, F ref) {
  OptionInfo info = MakeInfo("at", OptionKind::kNumbers, std::move(help));
  info.placeholder = "X,Y";
  return OptionalVectorOption<R, 2>(std::move(info), ref);
}

}  // namespace graspsynth::request
