#pragma once

// Python classes and enums made from the field lists of common/field_list.hpp: a result struct
// becomes a class with one read-only property per field (the field's name), a __repr__ of its
// brief fields (numbers rounded for the eye: python/repr.hpp) and to_dict() (every field; enums
// as their labels, nested results as dicts), and an enum with an EnumRange becomes a pybind11
// enum whose members are its ToString() names in capitals (TrialOutcome.NOT_LIFTED, .label
// "not_lifted"). The docstrings of the properties and members are given where each class or
// enum is bound (python/result_bindings.cpp), one per field or member.

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cstring>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>

#include "common/field_codec.hpp"
#include "common/field_list.hpp"
#include "python/bindings.hpp"
#include "python/repr.hpp"

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

/// The docstring of each field of a result class, {field name, text}: units, frame, meaning.
using FieldDocs = std::initializer_list<std::pair<const char*, const char*>>;

/// A field's value as the one-line repr shows it: numbers by ReprNumber, texts quoted, enum
/// members as Enum.MEMBER, vectors and tuples in brackets (a list of more than 4 items as its
/// count), a pose as its position, a nested result by its class's repr.
template <class T>
std::string ReprValue(const T& value) {
  using field_detail::FixedEigenVector;
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "True" : "False";
  } else if constexpr (std::is_floating_point_v<T>) {
    return ReprNumber(value);
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_same_v<T, std::string>) {
    return ReprText(value);
  } else if constexpr (std::is_enum_v<T>) {
    return ReprEnum(py::cast(value));
  } else if constexpr (std::is_same_v<T, Eigen::Isometry3d>) {
    return "pose(p=" + ReprValue(Eigen::Vector3d(value.translation())) + ")";
  } else if constexpr (field_detail::IsOptional<T>::value) {
    return value ? ReprValue(*value) : "None";
  } else if constexpr (FixedEigenVector<T> || field_detail::IsArray<T>::value ||
                       field_detail::IsVector<T>::value) {
    constexpr bool kList = field_detail::IsVector<T>::value;
    const size_t n = static_cast<size_t>(value.size());
    if (kList && n > 4) return "[" + std::to_string(n) + " items]";
    std::string text;
    for (size_t i = 0; i < n; ++i) text += (i ? ", " : "") + ReprValue(value[i]);
    return kList ? "[" + text + "]" : "(" + text + ")";
  } else {
    return py::repr(FieldToPython(value));
  }
}

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
    text += std::string(f.name) + "=" + ReprValue(value);
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
/// capitals and documented by `member_docs` (one per value, in order), with a `label` property
/// (the ToString() name the files write).
template <RangedEnum E>
py::enum_<E> BindEnum(py::handle scope, const char* name, const char* doc,
                      std::initializer_list<const char*> member_docs) {
  py::enum_<E> e(scope, name, doc);
  const auto upper = [](E v) {
    std::string member(ToString(v));
    for (char& c : member) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return member;
  };
  for (int k = 0; k <= static_cast<int>(EnumRange<E>::kLast); ++k) {
    const E v = static_cast<E>(k);
    const char* member_doc =
        static_cast<size_t>(k) < member_docs.size() ? member_docs.begin()[k] : nullptr;
    e.value(upper(v).c_str(), v, member_doc);
  }
  e.def_property_readonly(
      "label", [](E v) { return std::string(ToString(v)); },
      "the name the files write, e.g. \"not_lifted\"");
  // pybind11's own name and value, again with a docstring
  e.def_property_readonly("name", upper, "the member's name, e.g. \"NOT_LIFTED\"");
  e.def_property_readonly(
      "value", [](E v) { return static_cast<int>(v); }, "the member's number (0, 1, ...)");
  return e;
}

/// The text of `field` in `docs`; nullptr (no docstring: the package's test names it) when
/// it has none.
inline const char* FieldDoc(FieldDocs docs, const char* field) {
  for (const auto& [name, text] : docs) {
    if (std::strcmp(name, field) == 0) return text;
  }
  return nullptr;
}

/// Binds the result T as `name`: a read-only property per field of its list (documented by
/// `docs`), __repr__ (the brief fields, or every field when none is brief), to_dict() and
/// __eq__ (the same fields, compared by their job bytes: every number to the bit). `Options`
/// are pybind11's class options (a holder: std::shared_ptr<T> for a result that functions
/// return shared).
template <HasFields T, class... Options>
py::class_<T, Options...> BindFieldClass(py::handle scope, const char* name, const char* doc,
                                         FieldDocs docs) {
  py::class_<T, Options...> c(scope, name, doc);
  for (size_t k = 0; k < FieldCount<T>(); ++k) {
    const char* field = "";
    VisitField(T{}, k, [&](const Field& f, const auto&) { field = f.name; });
    c.def_property_readonly(
        field,
        [k](const T& t) {
          py::object out;
          VisitField(t, k, [&](const Field&, const auto& v) { out = FieldToPython(v); });
          return out;
        },
        FieldDoc(docs, field));
  }
  c.def("to_dict", &FieldsToDict<T>,
        "every field as a dict (enums as their labels, nested results as dicts)");
  c.def(
      "__repr__",
      [name](const T& t) {
        detail::AnyBrief brief;
        VisitFields(brief, t);
        std::string text;
        detail::ReprVisit visit{text, !brief.any};
        VisitFields(visit, t);
        return std::string(name) + "(" + text + ")";
      },
      "one line: the brief fields (numbers to 6 significant digits)");
  c.def("__eq__", [](const T& a, const T& b) { return EncodeFields(a) == EncodeFields(b); });
  return c;
}

}  // namespace graspsynth::python
