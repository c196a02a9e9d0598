// graspsynth._core: requests' options as Python keyword arguments (python/request_bindings.hpp).

#include "python/request_bindings.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <vector>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/text_input.hpp"
#include "request/analyze_request.hpp"
#include "request/generalize_request.hpp"
#include "request/run_request.hpp"
#include "request/select_request.hpp"
#include "request/simulate_request.hpp"
#include "request/synthesize_request.hpp"

namespace graspsynth::python {
namespace {

using request::OptionKind;

bool IsNumber(py::handle value) {
  return !py::isinstance<py::bool_>(value) &&
         (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
          py::hasattr(value, "__float__"));
}

double NumberOf(py::handle value, const std::string& where) {
  if (!IsNumber(value)) {
    throw InputError(where + ": needs a number, got " + std::string(py::repr(value)));
  }
  return value.cast<double>();
}

std::vector<double> NumbersOf(py::handle value, const std::string& where) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::iterable>(value)) {
    throw InputError(where + ": needs a sequence of numbers, got " + std::string(py::repr(value)));
  }
  std::vector<double> v;
  for (py::handle x : value) v.push_back(NumberOf(x, where));
  return v;
}

int64_t IntegerOf(py::handle value, const std::string& where) {
  if (py::isinstance<py::bool_>(value) || !PyIndex_Check(value.ptr())) {
    throw InputError(where + ": needs an integer, got " + std::string(py::repr(value)));
  }
  try {
    return value.cast<int64_t>();
  } catch (const py::cast_error&) {
    throw InputError(where + ": " + std::string(py::repr(value)) + " is out of range");
  }
}

// A member of one of the module's enums (SynthesisMethod.LINE) stands for its label ("line"),
// so that an option of texts takes either; anything else is returned as it is.
py::object TextOrLabel(py::handle value) {
  if (py::hasattr(py::type::of(value), "__members__") && py::hasattr(value, "label")) {
    return value.attr("label");
  }
  return py::reinterpret_borrow<py::object>(value);
}

// The requests request_options knows, for its message.
constexpr const char* kRequestNames =
    "synthesize, generalize, run, select, simulate, robustness, analyze, segment, fit_wrist_line";

}  // namespace

request::Value ValueFromPython(const request::OptionInfo& info, py::handle value,
                               const std::string& where) {
  if (info.optional && value.is_none()) return std::monostate{};
  switch (info.kind) {
    case OptionKind::kBool:
      if (!py::isinstance<py::bool_>(value)) {
        throw InputError(where + ": needs True or False, got " + std::string(py::repr(value)));
      }
      return value.cast<bool>();
    case OptionKind::kInt:
      return IntegerOf(value, where);
    case OptionKind::kUnsigned: {
      const int64_t v = IntegerOf(value, where);
      if (v < 0) throw InputError(where + ": needs an integer >= 0, got " + std::to_string(v));
      return static_cast<uint64_t>(v);
    }
    case OptionKind::kNumber:
      return NumberOf(value, where);
    case OptionKind::kText: {
      if (info.number_list && !py::isinstance<py::str>(value)) {
        std::string text;
        for (double x : NumbersOf(value, where))
          text += (text.empty() ? "" : ",") + ShortestNumber(x);
        if (text.empty()) throw InputError(where + ": no number given (an empty list)");
        return text;
      }
      const py::object text = TextOrLabel(value);
      if (!py::isinstance<py::str>(text)) {
        throw InputError(where + ": needs a text, got " + std::string(py::repr(value)));
      }
      return text.cast<std::string>();
    }
    case OptionKind::kTextList: {
      const py::object one = TextOrLabel(value);
      if (py::isinstance<py::str>(one)) {
        std::vector<std::string> texts;
        for (std::string_view t : SplitFields(one.cast<std::string>(), ',')) texts.emplace_back(t);
        return texts;
      }
      if (!py::isinstance<py::iterable>(value)) {
        throw InputError(where + ": needs texts, got " + std::string(py::repr(value)));
      }
      std::vector<std::string> texts;
      for (py::handle x : value) {
        const py::object text = TextOrLabel(x);
        if (!py::isinstance<py::str>(text)) {
          throw InputError(where + ": needs texts, got " + std::string(py::repr(x)));
        }
        texts.push_back(text.cast<std::string>());
      }
      return texts;
    }
    case OptionKind::kNumbers:
      if (value.is_none()) return std::vector<double>();
      return NumbersOf(value, where);
    case OptionKind::kNumberPair:
      return NumbersOf(value, where);
  }
  return request::Value();
}

py::object ValueToPython(const request::OptionInfo& info, const request::Value& value) {
  return std::visit(
      [&](const auto& v) -> py::object {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return py::none();
        } else if constexpr (std::is_same_v<T, std::vector<double>>) {
          if (info.kind == OptionKind::kNumbers && v.empty()) return py::none();
          return py::tuple(py::cast(v));
        } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
          return py::tuple(py::cast(v));  // an immutable default
        } else {
          return py::cast(v);
        }
      },
      value);
}

void RejectUnknownOptions(const std::vector<std::string>& names, const py::dict& given) {
  for (const auto& [key, value] : given) {
    const std::string name = py::str(key);
    if (std::find(names.begin(), names.end(), name) != names.end()) continue;
    const std::string nearest = request::NearestName(names, name);
    throw InputError("'" + name + "' is not an option" +
                     (nearest.empty() ? "" : " (did you mean '" + nearest + "'?)"));
  }
}

void BindRequests(py::module_& m) {
  m.def(
      "request_options",
      [](const std::string& name) -> py::list {
        if (name == "synthesize") return OptionDescriptions(request::SynthesizeOptions());
        if (name == "generalize") return OptionDescriptions(request::GeneralizeOptions());
        if (name == "run") return OptionDescriptions(request::RunOptions());
        if (name == "select") return OptionDescriptions(request::SelectOptions());
        if (name == "simulate") return OptionDescriptions(request::TrialRequestOptions());
        if (name == "robustness") return OptionDescriptions(request::RobustnessRequestOptions());
        if (name == "analyze") return OptionDescriptions(request::AnalyzeOptions());
        if (name == "segment") return OptionDescriptions(request::SegmentOptions());
        if (name == "fit_wrist_line") {
          return OptionDescriptions(request::WristLineRequestOptions());
        }
        throw InputError("no request '" + name + "' (" + kRequestNames + ")");
      },
      py::arg("request"), R"doc(
The options of a request (one of: synthesize, generalize, run, select, simulate, robustness,
analyze, segment, fit_wrist_line): a list of dicts with name, kind, default, help, choices and required, the one
description the command's flags, the Python keyword arguments and --config files are made
from.)doc");
}

}  // namespace graspsynth::python
