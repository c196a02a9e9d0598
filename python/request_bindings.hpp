#pragma once

/// @file
/// A request's options (request/option.hpp) as Python keyword arguments. The extension exposes
/// each request's option descriptions (request_options(name): name, kind, default, help,
/// choices, required), from which graspsynth/__init__.py makes each function's signature, with
/// every option an explicit keyword argument; the function hands the options it was given to
/// the extension as a dict, which RequestFromPython checks and reads with the checks every
/// front end shares.

#include <string>

#include "python/bindings.hpp"
#include "request/option.hpp"

namespace graspsynth::python {

/// The request value of the Python object `value` for an option of `info`. Throws InputError
/// "<where>: <why>" for a value of the wrong kind (a text where a number goes).
request::Value ValueFromPython(const request::OptionInfo& info, py::handle value,
                               const std::string& where);

/// The Python object of a request value (the signatures' defaults): bool, int, float, str,
/// list of str, tuple of float, or None for no numbers.
py::object ValueToPython(const request::OptionInfo& info, const request::Value& value);

/// Throws InputError for a key of `given` that names no option (with the nearest one).
void RejectUnknownOptions(const std::vector<std::string>& names, const py::dict& given);

/// The request of the defaults with the options of `given` (name -> Python value) over them,
/// each checked. Throws InputError naming the option.
template <class R>
R RequestFromPython(const request::OptionList<R>& options, const py::dict& given) {
  std::vector<std::string> names;
  for (const request::Option<R>& o : options) names.push_back(o.info.name);
  RejectUnknownOptions(names, given);
  R request{};
  for (const request::Option<R>& o : options) {
    if (!given.contains(o.info.name)) {
      if (o.info.required) throw InputError(o.info.name + " is required");
      continue;
    }
    const py::object value = given[py::str(o.info.name)];
    request::Apply(o, ValueFromPython(o.info, value, o.info.name), o.info.name, &request);
  }
  return request;
}

/// Each option of `options` as a dict: name, kind, default, help, choices, required, optional.
template <class R>
py::list OptionDescriptions(const request::OptionList<R>& options) {
  const R defaults{};
  py::list list;
  for (const request::Option<R>& o : options) {
    py::dict d;
    d["name"] = o.info.name;
    d["kind"] = static_cast<int>(o.info.kind);
    d["default"] =
        o.info.required ? py::object(py::none()) : ValueToPython(o.info, o.get(defaults));
    d["help"] = o.info.help;
    d["choices"] = o.info.choices;
    d["required"] = o.info.required;
    d["optional"] = o.info.optional;
    list.append(d);
  }
  return list;
}

}  // namespace graspsynth::python
