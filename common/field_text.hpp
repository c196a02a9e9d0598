#pragma once

/// @file
/// A struct with a field list (common/field_list.hpp) as JSON and as CSV: the fields that name a
/// JSON pointer (Field::json) or a CSV column (Field::csv), from the same list as the job bytes
/// and the Python classes. The JSON writer is a template over nlohmann's json types (the caller
/// links nlohmann), so that each report keeps its key order.

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/demand.hpp"
#include "common/field_codec.hpp"
#include "common/field_list.hpp"
#include "common/format.hpp"

namespace graspsynth {

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
inline std::string CsvText(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

/// No JSON form of a type of its own: every nested struct is written from its field list.
struct NoJsonForms {};

template <class Json, HasFields T, class Forms = NoJsonForms>
Json FieldsJson(const T& value, const Forms& forms = {});

namespace field_detail {

// A vector of structs with field lists (a concept, so that the element type is looked at only
// for vectors).
template <class T>
concept VectorOfFields = IsVector<T>::value && HasFields<typename T::value_type>;

// The JSON of one value: `forms` first (a report's own form of a nested type), then by type (a
// quaternion as [w, x, y, z], a pose as its 4 x 4 matrix by rows, a pair as [first, second]).
template <class Json, class T, class Forms>
Json JsonValue(const T& value, const Forms& forms) {
  if constexpr (std::is_invocable_v<const Forms&, const T&>) {
    return forms(value);
  } else if constexpr (std::is_enum_v<T>) {
    return std::string(ToString(value));
  } else if constexpr (FixedEigenVector<T>) {
    Json a = Json::array();
    for (int i = 0; i < value.size(); ++i) a.push_back(value[i]);
    return a;
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    return Json::array({value.w(), value.x(), value.y(), value.z()});
  } else if constexpr (std::is_same_v<T, Eigen::Isometry3d>) {
    Json rows = Json::array();
    for (int i = 0; i < 4; ++i) {
      Json row = Json::array();
      for (int j = 0; j < 4; ++j) row.push_back(value.matrix()(i, j));
      rows.push_back(std::move(row));
    }
    return rows;
  } else if constexpr (IsPair<T>::value) {
    return Json::array({JsonValue<Json>(value.first, forms), JsonValue<Json>(value.second, forms)});
  } else if constexpr (VectorOfFields<T>) {
    Json a = Json::array();
    for (const auto& v : value) a.push_back(FieldsJson<Json>(v, forms));
    return a;
  } else if constexpr (HasFields<T>) {
    return FieldsJson<Json>(value, forms);
  } else {
    return Json(value);
  }
}

// Writes the fields that name a JSON pointer into an object.
template <class Json, class Forms>
struct JsonWriter {
  Json& out;
  const Forms& forms;
  template <class T>
  void operator()(const Field& f, const T& value) {
    if (!f.json) return;
    const typename Json::json_pointer at(f.json);
    if (f.json_null) {
      out[at] = nullptr;
    } else if constexpr (IsOptional<T>::value) {
      if (value) {
        out[at] = JsonValue<Json>(*value, forms);
      } else if (!f.omit_empty) {
        out[at] = f.null_text ? Json(f.null_text) : Json(nullptr);
      }
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!(f.omit_empty && value.empty())) out[at] = JsonValue<Json>(value, forms);
    } else {
      out[at] = JsonValue<Json>(value, forms);
    }
  }
};

// A type with a CSV text: numbers, bools, enums, strings, Eigen vectors and optionals of them.
template <class T>
concept CsvScalar = std::is_arithmetic_v<T> || std::is_enum_v<T> || FixedEigenVector<T> ||
    std::is_same_v<T, std::string>;
template <class T>
concept CsvCapable = CsvScalar<T> ||(IsOptional<T>::value&& CsvScalar<typename T::value_type>);

// The CSV text of one value.
template <CsvCapable T>
std::string CsvValue(const Field& f, const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    return value ? "1" : "0";
  } else if constexpr (std::is_floating_point_v<T>) {
    return f.shortest ? ShortestNumber(value) : StreamNumber(value, 17);
  } else if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else if constexpr (std::is_enum_v<T>) {
    return std::string(ToString(value));
  } else if constexpr (FixedEigenVector<T>) {
    std::string text;
    for (int i = 0; i < value.size(); ++i) {
      if (i > 0) text += ',';
      text += CsvValue(f, value[i]);
    }
    return text;
  } else if constexpr (IsOptional<T>::value) {
    using V = typename T::value_type;
    if (value) return CsvValue(f, *value);
    if constexpr (FixedEigenVector<V>) return CsvValue(f, V(V::Constant(NAN)));
    return f.null_text ? f.null_text : "";
  } else {
    return CsvText(value);
  }
}

}  // namespace field_detail

/// The JSON object of `value`: each field that names a JSON pointer, at that pointer. `forms`
/// (a callable overloaded on some field types) gives the JSON of those types in place of the
/// default (numbers, strings, enums by ToString, Eigen vectors and vectors as arrays, nested
/// structs as objects of their own fields).
template <class Json, HasFields T, class Forms>
Json FieldsJson(const T& value, const Forms& forms) {
  Json out = Json::object();
  field_detail::JsonWriter<Json, Forms> writer{out, forms};
  VisitFields(writer, value);
  return out;
}

/// One cell of a CSV row, as the field list says.
struct CsvCell {
  int column = 0;
  std::string header;
  std::string text;
  bool conditional = false;  ///< an omit_empty column: in the table only when a row has it
  bool present = true;       ///< the value is there (for conditional columns)
};

/// The cells of `row`'s fields that name a CSV column, by column.
namespace field_detail {

// Collects the cells of the fields that name a CSV column.
struct CsvCollector {
  std::vector<CsvCell> cells;
  template <class T>
  void operator()(const Field& f, const T& value) {
    if (f.csv < 0) return;
    if constexpr (!CsvCapable<T>) {
      GS_DEMAND(false, std::string("a CSV column for the field ") + f.name +
                           ", of a type with no CSV text");
    } else {
      CsvCell c{f.csv, f.csv_header ? f.csv_header : f.name, CsvValue(f, value), f.omit_empty,
                true};
      if constexpr (IsOptional<T>::value) c.present = value.has_value();
      cells.push_back(std::move(c));
    }
  }
};

}  // namespace field_detail

template <HasFields T>
std::vector<CsvCell> CsvCells(const T& row) {
  field_detail::CsvCollector cells;
  VisitFields(cells, row);
  std::stable_sort(cells.cells.begin(), cells.cells.end(),
                   [](const CsvCell& a, const CsvCell& b) { return a.column < b.column; });
  return cells.cells;
}

/// The table of `rows` as CSV: a header line, then one line per row, the columns of the field
/// list by Field::csv. A conditional column (Field::omit_empty) is there only when some row has
/// its value.
template <HasFields T>
std::string FieldsCsv(const std::vector<T>& rows) {
  std::vector<std::vector<CsvCell>> cells;
  for (const T& row : rows) cells.push_back(CsvCells(row));
  const std::vector<CsvCell> header = CsvCells(T{});
  std::vector<bool> keep(header.size(), true);
  for (size_t k = 0; k < header.size(); ++k) {
    if (!header[k].conditional) continue;
    keep[k] = false;
    for (const auto& row : cells) keep[k] = keep[k] || row[k].present;
  }
  const auto line = [&](const std::vector<CsvCell>& row, bool headers) {
    std::string text;
    bool first = true;
    for (size_t k = 0; k < row.size(); ++k) {
      if (!keep[k]) continue;
      if (!first) text += ',';
      first = false;
      text += headers ? row[k].header : row[k].text;
    }
    return text + "\n";
  };
  std::string csv = line(header, true);
  for (const auto& row : cells) csv += line(row, false);
  return csv;
}

}  // namespace graspsynth
