#pragma once

/// @file
/// A job's result as bytes, so that it can travel between the processes of an MPI job or wait
/// in a resume folder, and come back as the same values. Every number keeps all its bits:
/// integers as 8 bytes, doubles as their IEEE 754 binary64 pattern, both in this machine's byte
/// order (the processes of one job run the same build on machines of one architecture). Strings
/// carry their length. The reader checks every length against what is left and throws
/// InputError naming its source, so a damaged file is an error, never a crash.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace graspsynth {

/// Appends values to a byte string.
class ByteWriter {
 public:
  void Bool(bool value) { UInt(value ? 1 : 0); }
  void Int(int64_t value);
  void UInt(uint64_t value);
  void Double(double value);
  void String(std::string_view value);
  /// An enumerator, as its underlying integer.
  template <typename Enum>
  void EnumValue(Enum value) {
    Int(static_cast<int64_t>(value));
  }
  void Doubles(const std::vector<double>& values);

  const std::string& bytes() const { return bytes_; }
  std::string Take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

/// Reads the values a ByteWriter wrote, in the same order. Each read throws InputError naming
/// the source and the byte offset when the bytes end too soon or hold a value out of range.
class ByteReader {
 public:
  /// `source` names the bytes in errors (a file, "rank 2's result").
  ByteReader(std::string_view bytes, std::string source);

  bool Bool();
  int64_t Int();
  /// An int64 that must lie in [lo, hi].
  int64_t IntIn(int64_t lo, int64_t hi);
  int Int32() { return static_cast<int>(IntIn(INT32_MIN, INT32_MAX)); }
  uint64_t UInt();
  double Double();
  std::string String();
  /// An enumerator in [0, last].
  template <typename Enum>
  Enum EnumValue(Enum last) {
    return static_cast<Enum>(IntIn(0, static_cast<int64_t>(last)));
  }
  std::vector<double> Doubles();
  /// Bytes not read yet.
  size_t left() const { return bytes_.size() - at_; }

  /// Throws InputError unless every byte was read.
  void Finish() const;

 private:
  [[noreturn]] void Fail(const std::string& what) const;
  void Take(void* out, size_t n);

  std::string_view bytes_;
  size_t at_ = 0;
  std::string source_;
};

/// Writes an optional as a presence flag, then the value by `write`.
template <typename T, typename Write>
void WriteOptional(ByteWriter& w, const std::optional<T>& value, Write write) {
  w.Bool(value.has_value());
  if (value) write(*value);
}

/// Reads what WriteOptional wrote; `read` returns the value.
template <typename Read>
auto ReadOptional(ByteReader& r, Read read) -> std::optional<decltype(read())> {
  if (!r.Bool()) return std::nullopt;
  return read();
}

/// A 64-bit FNV-1a hash of `bytes`, as 16 hexadecimal digits: a fingerprint of an input file
/// for a resumed run to see that it changed (not a cryptographic hash).
std::string Fingerprint(std::string_view bytes);

/// Fingerprint of bytes that come in pieces: Add them in order, then Hex() is the Fingerprint
/// of all of them together.
class FingerprintState {
 public:
  void Add(std::string_view bytes);
  std::string Hex() const;

 private:
  uint64_t hash_ = 14695981039346656037ULL;
};

}  // namespace graspsynth
