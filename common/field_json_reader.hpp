#pragma once

/// @file
/// A struct with a field list (common/field_list.hpp) read back from the JSON object that
/// FieldsJson (common/field_text.hpp) wrote: the reader of the same list, with JsonReader's
/// strict checks and messages (source, field path, expected and found value). Every field that
/// names a JSON pointer of one key ("/lift_m") is read from that key; an object with a key that
/// no field names is refused. The kinds of value: numbers (finite), integers, bools, strings,
/// enums by their ToString() name (RangedEnum), fixed-size Eigen vectors (that many numbers),
/// unit quaternions [w, x, y, z] (norm within kFieldQuaternionTolerance of 1, then normalized),
/// optionals (an absent or null key: empty), vectors of structs with field lists (arrays of
/// objects) and nested structs with field lists (objects).

#include <Eigen/Geometry>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "common/demand.hpp"
#include "common/field_codec.hpp"
#include "common/field_list.hpp"
#include "common/json_reader.hpp"

namespace graspsynth {

/// How far from 1 the norm of a quaternion read by ReadFieldsJson may be (written values are
/// rounded).
inline constexpr double kFieldQuaternionTolerance = 1e-5;

template <HasFields T>
void ReadFieldsJson(const JsonReader& object, T* out);

namespace field_detail {

// The key of a one-level JSON pointer ("/lift_m" -> "lift_m").
inline std::string_view JsonKey(const Field& f) {
  GS_DEMAND(f.json && f.json[0] == '/' && std::strchr(f.json + 1, '/') == nullptr,
            "ReadFieldsJson reads one-level JSON pointers only");
  return std::string_view(f.json + 1);
}

template <class T>
void ReadJsonValue(const JsonReader& r, T* out) {
  if constexpr (std::is_same_v<T, bool>) {
    *out = r.AsBool();
  } else if constexpr (std::is_floating_point_v<T>) {
    *out = r.AsNumber();
  } else if constexpr (std::is_integral_v<T>) {
    *out = static_cast<T>(r.AsInteger(INT32_MIN, INT32_MAX));
  } else if constexpr (RangedEnum<T>) {
    const std::string text = r.AsString();
    std::string names;
    for (int i = 0; i <= static_cast<int>(EnumRange<T>::kLast); ++i) {
      const T value = static_cast<T>(i);
      if (text == ToString(value)) {
        *out = value;
        return;
      }
      names += (i > 0 ? ", " : "") + std::string(ToString(value));
    }
    r.Fail("one of " + names);
  } else if constexpr (std::is_same_v<T, std::string>) {
    *out = r.AsString();
  } else if constexpr (FixedEigenVector<T>) {
    *out = r.AsNumbers(static_cast<int>(T::RowsAtCompileTime));
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    const Eigen::VectorXd q = r.AsNumbers(4);
    if (std::abs(q.norm() - 1.0) > kFieldQuaternionTolerance)
      r.Fail("a unit quaternion [w, x, y, z]");
    *out = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
  } else if constexpr (IsOptional<T>::value) {
    if (!r.present() || r.IsNull()) {
      out->reset();
    } else {
      typename T::value_type value{};
      ReadJsonValue(r, &value);
      *out = std::move(value);
    }
  } else if constexpr (IsVector<T>::value && HasFields<typename T::value_type>) {
    out->clear();
    for (const JsonReader& element : r.AsArray()) {
      typename T::value_type value{};
      ReadFieldsJson(element, &value);
      out->push_back(std::move(value));
    }
  } else {
    static_assert(HasFields<T>, "ReadFieldsJson cannot read this field's type");
    ReadFieldsJson(r, out);
  }
}

// Reads every field that names a JSON pointer; collects the keys.
struct JsonFieldReader {
  const JsonReader& object;
  std::vector<std::string_view> keys;
  template <class T>
  void operator()(const Field& f, T& value) {
    if (!f.json) return;
    const std::string_view key = JsonKey(f);
    keys.push_back(key);
    ReadJsonValue(object.Field(key), &value);
  }
};

}  // namespace field_detail

/// Reads `object` (a JSON object) into `out`, field by field (see the file comment). Throws
/// InputError naming the field's path for a missing field (other than an optional), a value of
/// the wrong kind or out of range, and for a key that no field names.
template <HasFields T>
void ReadFieldsJson(const JsonReader& object, T* out) {
  object.AsObject();
  field_detail::JsonFieldReader reader{object, {}};
  VisitFields(reader, *out);
  for (const std::string& key : object.Keys()) {
    bool known = false;
    std::string names;
    for (std::string_view k : reader.keys) {
      known = known || k == key;
      names += (names.empty() ? "" : ", ") + std::string(k);
    }
    if (!known) object.Field(key).Fail("only the fields " + names + " here");
  }
}

}  // namespace graspsynth
