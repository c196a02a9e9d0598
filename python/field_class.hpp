#pragma once

// Python classes and enums made from the field lists of common/field_list.hpp: a result struct
// becomes a class with one read-only property per field (the field's name), a __repr__ of its
// brief fields and to_dict() (every field; enums as their labels, nested results as dicts), and
// an enum with an EnumRange becomes a pybind11 enum whose members are its ToString() names in
// capitals (TrialOutcome.NOT_LIFTED, .label "not_lifted").

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <string>
#include <type_traits>

#include "common/field_codec.hpp"
#include "common/field_list.hpp"
#include "python/bindings.hpp"

namespace graspsynth::python {

namespace py = pybind11;

/// A field's value as a Python object: numbers, strings, enums (bound with BindEnum), tuples
/// for Eigen vectors and fixed arrays, a 4 x 4 array for a pose, lists for vectors, None for an
/// empty optional, a bound class for a nested result.
template <class T>
py::object FieldToPython(const T& value) {
  using field_detail::FixedEigenVector;
  if constexpr (std::is_same_v<T, Eigen::Isometry3d>) {
    py::array_t<double> pose = NewArray({4, 4});
    WriteMatrix(value, pose.mutable_data());
    return pose;
  } else if constexpr (field_detail::IsOptional<T>::value) {
    return value ? FieldToPython(*value) : py::none();
  } else if constexpr (FixedEigenVector<T> || field_detail::IsArray<T>::value) {
    py::tuple t(value.size());
    for (py::ssize_t i = 0; i < static_cast<py::ssize_t>(value.size()); ++i) {
      t[i] = value[static_cast<size_t>(i)];
    }
    return t;
  } else if constexpr (field_detail::IsVector<T>::value) {
    py::list l;
    for (const auto& v : value) l.append(FieldToPython(v));
    return l;
  } else {
    return py::cast(value);
  }
}

/// A field's value for to_dict(): as FieldToPython, but enums as their labels and nested
/// results as dicts, so that pandas makes columns of them.
template <class T>
py::object FieldToPlain(const T& value);

namespace detail {

// Puts every field of a result into a dict.
struct DictVisit {
  py::dict& d;
  template <class T>
  void operator()(const Field& f, const T& value) {
    d[f.name] = FieldToPlain(value);
  }
};

// Writes the brief fields of a result as "name=repr, ...".
struct ReprVisit {
  std::string& text;
  bool all;
  template <class T>
  void operator()(const Field& f, const T& value) {
    if (!all && !f.brief) return;
    if (!text.empty()) text += ", ";
    const py::object v = FieldToPython(value);
    // an enum member as TrialOutcome.SUCCESS, not its repr <TrialOutcome.SUCCESS: 0>
    const bool member = py::hasattr(py::type::of(v), "__members__");
    text += std::string(f.name) + "=" + std::string(member ? py::str(v) : py::repr(v));
  }
};

// True when some field of T is brief.
struct AnyBrief {
  bool any = false;
  template <class T>
  void operator()(const Field& f, const T&) {
    any = any || f.brief;
  }
};

}  // namespace detail

/// Every field of `value` as a dict {name: FieldToPlain(value)}.
template <HasFields T>
py::dict FieldsToDict(const T& value) {
  py::dict d;
  detail::DictVisit visit{d};
  VisitFields(visit, value);
  return d;
}

template <class T>
py::object FieldToPlain(const T& value) {
  if constexpr (field_detail::IsOptional<T>::value) {
    return value ? FieldToPlain(*value) : py::none();
  } else if constexpr (std::is_enum_v<T>) {
    return py::str(std::string(ToString(value)));
  } else if constexpr (HasFields<T>) {
    return FieldsToDict(value);
  } else if constexpr (field_detail::IsVector<T>::value) {
    py::list l;
    for (const auto& v : value) l.append(FieldToPlain(v));
    return l;
  } else {
    return FieldToPython(value);
  }
}

/// Binds the enum E as `name`: a member per value of its EnumRange, named by ToString() in
/// capitals, with a `label` property (the ToString() name the files write).
template <RangedEnum E>
py::enum_<E> BindEnum(py::handle scope, const char* name, const char* doc) {
  py::enum_<E> e(scope, name, doc);
  for (int k = 0; k <= static_cast<int>(EnumRange<E>::kLast); ++k) {
    const E v = static_cast<E>(k);
    std::string member(ToString(v));
    for (char& c : member) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    e.value(member.c_str(), v);
  }
  e.def_property_readonly(
      "label", [](E v) { return std::string(ToString(v)); },
      "the name the files write, e.g. \"not_lifted\"");
  return e;
}

/// Binds the result T as `name`: a read-only property per field of its list, __repr__ (the
/// brief fields, or every field when none is brief), to_dict() and __eq__ (the same fields,
/// compared by their job bytes: every number to the bit). `Options` are pybind11's class
/// options (a holder: std::shared_ptr<T> for a result that functions return shared).
template <HasFields T, class... Options>
py::class_<T, Options...> BindFieldClass(py::handle scope, const char* name, const char* doc) {
  py::class_<T, Options...> c(scope, name, doc);
  for (size_t k = 0; k < FieldCount<T>(); ++k) {
    const char* field = "";
    VisitField(T{}, k, [&](const Field& f, const auto&) { field = f.name; });
    c.def_property_readonly(field, [k](const T& t) {
      py::object out;
      VisitField(t, k, [&](const Field&, const auto& v) { out = FieldToPython(v); });
      return out;
    });
  }
  c.def("to_dict", &FieldsToDict<T>,
        "every field as a dict (enums as their labels, nested results as dicts)");
  c.def("__repr__", [name](const T& t) {
    detail::AnyBrief brief;
    VisitFields(brief, t);
    std::string text;
    detail::ReprVisit visit{text, !brief.any};
    VisitFields(visit, t);
    return std::string(name) + "(" + text + ")";
  });
  c.def("__eq__", [](const T& a, const T& b) { return EncodeFields(a) == EncodeFields(b); });
  return c;
}

}  // namespace graspsynth::python
