#pragma once

/// @file
/// One description per result struct: a struct lists its fields once, in a free function
///
///     template <class V, class Row> requires SameStruct<Row, StudyRow>
///     void VisitFields(V& v, Row& r) {
///       v(Field("theta_deg").Json("/theta_deg").Csv(1), r.theta_deg);
///       ...
///     }
///
/// beside it (found by argument-dependent lookup), and every reader and writer of the struct is
/// made from that list: the job bytes (common/field_codec.hpp: every field, in the list's order),
/// the JSON and CSV writers (common/field_text.hpp: the fields that name a JSON pointer or a CSV
/// column) and the Python classes (python/field_class.hpp: every field, a read-only property).
/// A new field is one line here; which text files carry it is said on that line.
///
/// Drake's `Serialize(Archive*)` with `DRAKE_NVP` is the model (common/name_value.h); a visitor
/// over (Field, member) pairs keeps it in plain C++ with no dependency, and `Row` is a template
/// parameter so that one list serves reading (StudyRow&) and writing (const StudyRow&).

#include <concepts>
#include <cstddef>
#include <type_traits>

namespace graspsynth {

/// How one field of a result shows in the outputs made from its field list. Built with the
/// chained setters: `Field("passed").Json("/passed").Csv(14).Brief()`.
struct Field {
  /// The member's name: the Python property and to_dict() key.
  const char* name = "";
  /// JSON pointer of the field in its struct's JSON object ("/robustness/score"; an index makes
  /// an array: "/robustness/ci95/0"); nullptr: not in the JSON.
  const char* json = nullptr;
  /// The field's CSV column (0-based; the table sorts by it); -1: not in the CSV.
  int csv = -1;
  /// The column's header; nullptr: `name`. A two-vector field names both columns ("x,y").
  const char* csv_header = nullptr;
  /// An empty optional's text in the JSON and the CSV ("" or "no_library"); nullptr: JSON null.
  const char* null_text = nullptr;
  /// An empty optional or text is left out of the JSON object (an optional is not written as
  /// null), and an optional's CSV columns are there only when some row of the table has a
  /// value.
  bool omit_empty = false;
  /// Written as JSON null whatever the value (a figure that is not meaningful in this row).
  bool json_null = false;
  /// CSV numbers in the shortest form that reads back (ShortestNumber); otherwise 17 digits.
  bool shortest = false;
  /// Shown by the Python class's __repr__.
  bool brief = false;

  constexpr explicit Field(const char* field_name) : name(field_name) {}

  constexpr Field Json(const char* pointer) const {
    Field f = *this;
    f.json = pointer;
    return f;
  }
  constexpr Field Csv(int column, const char* header = nullptr) const {
    Field f = *this;
    f.csv = column;
    f.csv_header = header;
    return f;
  }
  constexpr Field NullText(const char* text) const {
    Field f = *this;
    f.null_text = text;
    return f;
  }
  constexpr Field OmitEmpty() const {
    Field f = *this;
    f.omit_empty = true;
    return f;
  }
  constexpr Field JsonNullIf(bool null) const {
    Field f = *this;
    f.json_null = null;
    return f;
  }
  constexpr Field Shortest() const {
    Field f = *this;
    f.shortest = true;
    return f;
  }
  constexpr Field Brief() const {
    Field f = *this;
    f.brief = true;
    return f;
  }
};

/// True when `Row` is `Struct` or `const Struct` (the two ways a field list is visited).
template <class Row, class Struct>
concept SameStruct = std::same_as<std::remove_const_t<Row>, Struct>;

/// The range of an enum whose enumerators are 0, 1, ..., kLast: specialize beside the enum's
/// field lists with `static constexpr E kLast`. The job bytes refuse a value outside it, and the
/// Python enum lists every value in it by its ToString() name.
template <class E>
struct EnumRange;

namespace field_detail {

// A visitor that does nothing: to ask whether a type has a field list.
struct NoVisit {
  template <class T>
  void operator()(const Field&, const T&) {}
};

// Counts the fields of a list.
struct CountVisit {
  size_t n = 0;
  template <class T>
  void operator()(const Field&, const T&) {
    ++n;
  }
};

// Calls f on the index-th field only.
template <class F>
struct OneVisit {
  size_t index;
  F& f;
  size_t at = 0;
  template <class V>
  void operator()(const Field& field, const V& value) {
    if (at++ == index) f(field, value);
  }
};

}  // namespace field_detail

/// True for a struct with a field list (a VisitFields found for it).
template <class T>
concept HasFields = requires(field_detail::NoVisit& v, const T& t) {
  VisitFields(v, t);
};

/// True for an enum with an EnumRange.
template <class E>
concept RangedEnum = std::is_enum_v<E> && requires {
  EnumRange<E>::kLast;
};

/// The number of fields in T's list.
template <HasFields T>
size_t FieldCount() {
  field_detail::CountVisit count;
  const T t{};
  VisitFields(count, t);
  return count.n;
}

/// Calls `f(field, value)` on the `index`-th field of `t` (0-based; nothing when out of range).
template <HasFields T, class F>
void VisitField(const T& t, size_t index, F&& f) {
  field_detail::OneVisit<F> one{index, f};
  VisitFields(one, t);
}

}  // namespace graspsynth
