#pragma once

/// @file
/// The text of numbers and values in the Python classes' __repr__: one line a reader takes in
/// at a glance. Numbers have 6 significant digits, and a rounding residue (|x| < 1e-12, such
/// as 5.55e-17 where 0 is meant) is shown as 0; the values themselves are not changed (the
/// properties and to_dict() give every bit).

#include <pybind11/pybind11.h>

#include <cmath>
#include <cstdio>
#include <string>

namespace graspsynth::python {

namespace py = pybind11;

/// Below this magnitude a number is shown as 0 (a rounding residue of SI values: m, rad, s).
inline constexpr double kReprZero = 1e-12;

/// `x` as a repr shows it: 6 significant digits, always with a point or exponent (a float
/// reads as one: "1.0", "0.95", "1.5e-07"), "0.0" for |x| < kReprZero, "nan", "inf", "-inf".
inline std::string ReprNumber(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (std::abs(x) < kReprZero) return "0.0";
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", x);
  std::string s(text);
  if (s.find_first_of(".e") == std::string::npos) s += ".0";
  return s;
}

/// `text` quoted as Python's repr() quotes a str.
inline std::string ReprText(const std::string& text) { return py::repr(py::str(text)); }

/// A enum member as `Enum.MEMBER` (its str(), not pybind11's `<Enum.MEMBER: 0>`).
inline std::string ReprEnum(const py::object& member) { return py::str(member); }

}  // namespace graspsynth::python
