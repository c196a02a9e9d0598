#pragma once

/// @file
/// Strict reading of JSON input files. A JsonReader is one value of a parsed document together
/// with where it is: the source (a file name) and the field path from the document's root, e.g.
/// `entries[3].motion.waypoints[0].quaternion`. Every check throws InputError with one wording:
///
///     <source>: field '<path>': expected <what was expected>, found <the value found>
///
/// (`found nothing` for a missing field; `the document` in place of the field for the root).
/// Bare non-finite tokens (NaN, Infinity, as Python's json module writes them) are accepted by
/// the parser and rejected by the number checks, so that the error names their field.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/input_file.hpp"

namespace graspsynth {

/// One value of a parsed JSON document, with its source and field path (see the file comment).
/// Cheap to copy: the document is shared.
class JsonReader {
 public:
  /// Parses `text`. Throws InputError "<source>: not valid JSON: <the parser's message, with
  /// the line and column>" when it is not JSON.
  static JsonReader Parse(std::string_view text, const std::string& source);
  /// Reads (common/input_file.hpp's ReadInputFile, as a file of `kind`) and parses the file at
  /// `path` (the source is the path). Throws InputError when the file cannot be read, is not a
  /// regular file, is over the kind's size limit or is not JSON.
  static JsonReader Load(const std::filesystem::path& path,
                         const InputFileKind& kind = input_kind::kJson);

  /// The file or other source the document came from.
  const std::string& source() const;
  /// The field path from the root ("" for the root itself).
  const std::string& path() const { return path_; }
  /// False for a field that is absent from its object.
  bool present() const { return node_ != nullptr; }
  /// The value as compact JSON (at most 60 characters), or "nothing" when absent.
  std::string Shown() const;
  /// Throws InputError "<source>: field '<path>': expected <expected>, found <Shown()>".
  [[noreturn]] void Fail(std::string_view expected) const;

  /// @name Kinds of this value (false when absent)
  ///@{
  bool IsObject() const;
  bool IsArray() const;
  bool IsString() const;
  bool IsNumber() const;
  bool IsNull() const;  ///< present and null
  ///@}

  /// @name This value, checked
  /// Each throws InputError (the wording above) when the value is absent or of another kind.
  ///@{
  /// This value, which must be an object.
  const JsonReader& AsObject() const;
  /// A finite number.
  double AsNumber() const;
  /// A finite number in [lo, hi].
  double AsNumberIn(double lo, double hi) const;
  /// A finite number > 0.
  double AsPositiveNumber() const;
  /// An integer in [lo, hi].
  int64_t AsInteger(int64_t lo, int64_t hi) const;
  /// A non-negative integer.
  uint64_t AsUnsigned() const;
  /// true or false.
  bool AsBool() const;
  /// A string.
  std::string AsString() const;
  /// The elements of an array (paths `<path>[i]`).
  std::vector<JsonReader> AsArray() const;
  /// An array of exactly `count` finite numbers, each in [lo, hi].
  Eigen::VectorXd AsNumbers(int count, double lo = -INFINITY, double hi = INFINITY) const;
  ///@}

  /// @name Fields of this object
  /// Each requires this value to be an object. The typed ones are Field(key).As...().
  ///@{
  /// Whether the object has `key`.
  bool Has(std::string_view key) const;
  /// The keys of the object, in file order.
  std::vector<std::string> Keys() const;
  /// Throws InputError naming the first key that is not in `known`.
  void RejectUnknownKeys(std::initializer_list<std::string_view> known) const;
  /// The field `key` (path `<path>.key`); absent (present() false) when the object lacks it.
  JsonReader Field(std::string_view key) const;
  /// The field `key`, or std::nullopt when the object lacks it.
  std::optional<JsonReader> OptionalField(std::string_view key) const;
  /// Checks that the string field `key` is `expected` (e.g. a format tag).
  void ExpectString(std::string_view key, std::string_view expected) const;

  JsonReader Object(std::string_view key) const { return Field(key).AsObject(); }
  double Number(std::string_view key) const { return Field(key).AsNumber(); }
  double NumberIn(std::string_view key, double lo, double hi) const {
    return Field(key).AsNumberIn(lo, hi);
  }
  double PositiveNumber(std::string_view key) const { return Field(key).AsPositiveNumber(); }
  int64_t Integer(std::string_view key, int64_t lo, int64_t hi) const {
    return Field(key).AsInteger(lo, hi);
  }
  uint64_t Unsigned(std::string_view key) const { return Field(key).AsUnsigned(); }
  bool Bool(std::string_view key) const { return Field(key).AsBool(); }
  std::string String(std::string_view key) const { return Field(key).AsString(); }
  std::vector<JsonReader> Array(std::string_view key) const { return Field(key).AsArray(); }
  Eigen::VectorXd Numbers(std::string_view key, int count, double lo = -INFINITY,
                          double hi = INFINITY) const {
    return Field(key).AsNumbers(count, lo, hi);
  }
  /// An array of 3 finite numbers.
  Eigen::Vector3d Vector3(std::string_view key) const;
  /// An array of 4 finite numbers in the order w, x, y, z, as written (not normalized).
  Eigen::Quaterniond Quaternion(std::string_view key) const;
  /// A Quaternion whose norm is within `tolerance` of 1, as written (not normalized).
  Eigen::Quaterniond UnitQuaternion(std::string_view key, double tolerance) const;
  /// Number(key), or std::nullopt when the object lacks `key`.
  std::optional<double> OptionalNumber(std::string_view key) const;
  ///@}

 private:
  struct Document;
  JsonReader(std::shared_ptr<const Document> document, const void* node, std::string path);
  JsonReader Child(const void* node, std::string path) const;
  void RequireObject() const;

  std::shared_ptr<const Document> document_;
  const void* node_;  // the nlohmann value, or nullptr when absent
  std::string path_;
};

}  // namespace graspsynth
