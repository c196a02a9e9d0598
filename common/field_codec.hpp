#pragma once

/// @file
/// A struct with a field list (common/field_list.hpp) as job bytes (common/byte_codec.hpp):
/// every field in the list's order, every number to the bit. The bytes of each kind of value:
/// bool, int, uint64 and enums as 8 bytes (an enum refused outside its EnumRange), double as
/// its bit pattern, strings and vectors with their length first, std::optional as a presence
/// flag then the value, fixed-size arrays and Eigen vectors as their numbers, a quaternion as w,
/// x, y, z, an isometry as its 4 x 4 matrix (column by column), a pair as its first then its
/// second, a nested struct as its own field list.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/byte_codec.hpp"
#include "common/field_list.hpp"

namespace graspsynth {

namespace field_detail {

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

template <class T>
struct IsVector : std::false_type {};
template <class T>
struct IsVector<std::vector<T>> : std::true_type {};

template <class T>
struct IsPair : std::false_type {};
template <class A, class B>
struct IsPair<std::pair<A, B>> : std::true_type {};

template <class T>
struct IsArray : std::false_type {};
template <class T, size_t N>
struct IsArray<std::array<T, N>> : std::true_type {};

// A fixed-size Eigen vector of doubles (Vector2d, Vector3d).
template <class T>
concept FixedEigenVector =
    std::is_base_of_v<Eigen::MatrixBase<T>, T> && T::ColsAtCompileTime == 1 &&
    T::RowsAtCompileTime > 0 && std::is_same_v<typename T::Scalar, double>;

template <class T>
void WriteValue(ByteWriter& w, const T& value);

// Writes every field of a struct.
struct FieldWriter {
  ByteWriter& w;
  template <class T>
  void operator()(const Field&, const T& value) {
    WriteValue(w, value);
  }
};

template <class T>
void WriteValue(ByteWriter& w, const T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    w.Bool(value);
  } else if constexpr (std::is_same_v<T, double>) {
    w.Double(value);
  } else if constexpr (std::is_same_v<T, uint64_t>) {
    w.UInt(value);
  } else if constexpr (std::is_integral_v<T>) {
    w.Int(value);
  } else if constexpr (std::is_enum_v<T>) {
    w.EnumValue(value);
  } else if constexpr (std::is_same_v<T, std::string>) {
    w.String(value);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    w.Doubles(value);
  } else if constexpr (IsOptional<T>::value) {
    WriteOptional(w, value, [&](const auto& v) { WriteValue(w, v); });
  } else if constexpr (IsVector<T>::value) {
    w.UInt(value.size());
    for (const auto& v : value) WriteValue(w, v);
  } else if constexpr (IsArray<T>::value) {
    for (const auto& v : value) WriteValue(w, v);
  } else if constexpr (FixedEigenVector<T>) {
    for (int i = 0; i < value.size(); ++i) w.Double(value[i]);
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    for (double c : {value.w(), value.x(), value.y(), value.z()}) w.Double(c);
  } else if constexpr (std::is_same_v<T, Eigen::Isometry3d>) {
    for (int i = 0; i < 16; ++i) w.Double(value.matrix().data()[i]);
  } else if constexpr (IsPair<T>::value) {
    WriteValue(w, value.first);
    WriteValue(w, value.second);
  } else {
    static_assert(HasFields<T>, "a field of a type the job bytes cannot write");
    FieldWriter fields{w};
    VisitFields(fields, value);
  }
}

template <class T>
void ReadValue(ByteReader& r, T& value);

// Reads every field of a struct.
struct FieldReader {
  ByteReader& r;
  template <class T>
  void operator()(const Field&, T& value) {
    ReadValue(r, value);
  }
};

template <class T>
void ReadValue(ByteReader& r, T& value) {
  if constexpr (std::is_same_v<T, bool>) {
    value = r.Bool();
  } else if constexpr (std::is_same_v<T, double>) {
    value = r.Double();
  } else if constexpr (std::is_same_v<T, uint64_t>) {
    value = r.UInt();
  } else if constexpr (std::is_same_v<T, int>) {
    value = r.Int32();
  } else if constexpr (std::is_same_v<T, int64_t>) {
    value = r.Int();
  } else if constexpr (std::is_enum_v<T>) {
    static_assert(RangedEnum<T>, "an enum field needs an EnumRange");
    value = r.EnumValue(EnumRange<T>::kLast);
  } else if constexpr (std::is_same_v<T, std::string>) {
    value = r.String();
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    value = r.Doubles();
  } else if constexpr (IsOptional<T>::value) {
    value.reset();
    if (r.Bool()) ReadValue(r, value.emplace());
  } else if constexpr (IsVector<T>::value) {
    // every value takes at least 8 bytes: a longer count is damage, not a huge allocation.
    const int64_t n = r.IntIn(0, static_cast<int64_t>(r.left() / 8));
    value.assign(static_cast<size_t>(n), typename T::value_type{});
    for (auto& v : value) ReadValue(r, v);
  } else if constexpr (IsArray<T>::value) {
    for (auto& v : value) ReadValue(r, v);
  } else if constexpr (FixedEigenVector<T>) {
    for (int i = 0; i < value.size(); ++i) value[i] = r.Double();
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    const double qw = r.Double(), qx = r.Double(), qy = r.Double(), qz = r.Double();
    value = Eigen::Quaterniond(qw, qx, qy, qz);
  } else if constexpr (std::is_same_v<T, Eigen::Isometry3d>) {
    for (int i = 0; i < 16; ++i) value.matrix().data()[i] = r.Double();
  } else if constexpr (IsPair<T>::value) {
    ReadValue(r, value.first);
    ReadValue(r, value.second);
  } else {
    static_assert(HasFields<T>, "a field of a type the job bytes cannot read");
    FieldReader fields{r};
    VisitFields(fields, value);
  }
}

}  // namespace field_detail

/// The bytes of `value`: a struct with a field list (its fields in its list's order) or any
/// value the file comment names, such as a vector of such structs.
template <class T>
std::string EncodeFields(const T& value) {
  ByteWriter w;
  field_detail::WriteValue(w, value);
  return w.Take();
}

/// The value EncodeFields wrote. Throws InputError naming `source` (and the byte offset) for
/// bytes that end too soon, hold a value out of range, or go on after the value.
template <class T>
T DecodeFields(std::string_view bytes, const std::string& source) {
  ByteReader r(bytes, source);
  T value;
  field_detail::ReadValue(r, value);
  r.Finish();
  return value;
}

}  // namespace graspsynth
