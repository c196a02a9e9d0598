#include "common/byte_codec.hpp"

#include <cstdio>
#include <cstring>
#include <utility>

#include "common/errors.hpp"

namespace graspsynth {

void ByteWriter::Int(int64_t value) {
  char b[sizeof value];
  std::memcpy(b, &value, sizeof value);
  bytes_.append(b, sizeof b);
}

void ByteWriter::UInt(uint64_t value) {
  char b[sizeof value];
  std::memcpy(b, &value, sizeof value);
  bytes_.append(b, sizeof b);
}

void ByteWriter::Double(double value) {
  char b[sizeof value];
  std::memcpy(b, &value, sizeof value);
  bytes_.append(b, sizeof b);
}

void ByteWriter::String(std::string_view value) {
  UInt(value.size());
  bytes_.append(value);
}

void ByteWriter::Doubles(const std::vector<double>& values) {
  UInt(values.size());
  for (double v : values) Double(v);
}

ByteReader::ByteReader(std::string_view bytes, std::string source)
    : bytes_(bytes), source_(std::move(source)) {}

void ByteReader::Fail(const std::string& what) const {
  throw InputError(source_ + ": byte " + std::to_string(at_) + ": " + what);
}

void ByteReader::Take(void* out, size_t n) {
  if (bytes_.size() - at_ < n) {
    Fail("ends after " + std::to_string(bytes_.size()) + " bytes, " + std::to_string(n) +
         " more expected");
  }
  std::memcpy(out, bytes_.data() + at_, n);
  at_ += n;
}

bool ByteReader::Bool() {
  const uint64_t v = UInt();
  if (v > 1) Fail("a flag of " + std::to_string(v) + " (0 or 1 expected)");
  return v == 1;
}

int64_t ByteReader::Int() {
  int64_t v = 0;
  Take(&v, sizeof v);
  return v;
}

int64_t ByteReader::IntIn(int64_t lo, int64_t hi) {
  const int64_t v = Int();
  if (v < lo || v > hi) {
    Fail("the value " + std::to_string(v) + " is outside [" + std::to_string(lo) + ", " +
         std::to_string(hi) + "]");
  }
  return v;
}

uint64_t ByteReader::UInt() {
  uint64_t v = 0;
  Take(&v, sizeof v);
  return v;
}

double ByteReader::Double() {
  double v = 0.0;
  Take(&v, sizeof v);
  return v;
}

std::string ByteReader::String() {
  const uint64_t n = UInt();
  if (n > bytes_.size() - at_) {
    Fail("a text of " + std::to_string(n) + " bytes, but only " +
         std::to_string(bytes_.size() - at_) + " are left");
  }
  std::string s(bytes_.substr(at_, n));
  at_ += n;
  return s;
}

std::vector<double> ByteReader::Doubles() {
  const uint64_t n = UInt();
  if (n > (bytes_.size() - at_) / sizeof(double)) {
    Fail(std::to_string(n) + " numbers, but only " + std::to_string(bytes_.size() - at_) +
         " bytes are left");
  }
  std::vector<double> v(n);
  for (double& x : v) x = Double();
  return v;
}

void ByteReader::Finish() const {
  if (at_ != bytes_.size()) {
    throw InputError(source_ + ": " + std::to_string(bytes_.size() - at_) +
                     " bytes left over after byte " + std::to_string(at_));
  }
}

void FingerprintState::Add(std::string_view bytes) {
  for (unsigned char c : bytes) {
    hash_ ^= c;
    hash_ *= 1099511628211ULL;
  }
}

std::string FingerprintState::Hex() const {
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(hash_));
  return hex;
}

std::string Fingerprint(std::string_view bytes) {
  FingerprintState state;
  state.Add(bytes);
  return state.Hex();
}

}  // namespace graspsynth
