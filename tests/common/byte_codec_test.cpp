// Tests of common/byte_codec.hpp: values come back bit for bit, and bytes that are not what the
// reader expects are an InputError naming the source and the byte, never a crash.

#include "common/byte_codec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;

enum class Colour { kRed, kGreen, kBlue };

TEST(ByteCodec, ValuesComeBackBitForBit) {
  const double tiny = std::numeric_limits<double>::denorm_min();
  ByteWriter w;
  w.Bool(true);
  w.Int(-1234567890123LL);
  w.UInt(std::numeric_limits<uint64_t>::max());
  w.Double(0.1 + 0.2);
  w.Double(-0.0);
  w.Double(tiny);
  w.String(std::string("a\0b", 3));
  w.EnumValue(Colour::kBlue);
  w.Doubles({1.5, std::nextafter(1.0, 2.0)});
  WriteOptional(w, std::optional<double>(), [&](double v) { w.Double(v); });
  WriteOptional(w, std::optional<double>(2.5), [&](double v) { w.Double(v); });

  ByteReader r(w.bytes(), "test");
  EXPECT_TRUE(r.Bool());
  EXPECT_EQ(r.Int(), -1234567890123LL);
  EXPECT_EQ(r.UInt(), std::numeric_limits<uint64_t>::max());
  const double sum = r.Double();
  EXPECT_EQ(std::memcmp(&sum, &static_cast<const double&>(0.1 + 0.2), sizeof sum), 0);
  const double zero = r.Double();
  EXPECT_TRUE(std::signbit(zero));
  EXPECT_EQ(r.Double(), tiny);
  EXPECT_EQ(r.String(), std::string("a\0b", 3));
  EXPECT_EQ(r.EnumValue(Colour::kBlue), Colour::kBlue);
  EXPECT_EQ(r.Doubles(), (std::vector<double>{1.5, std::nextafter(1.0, 2.0)}));
  EXPECT_FALSE(ReadOptional(r, [&] { return r.Double(); }).has_value());
  EXPECT_EQ(ReadOptional(r, [&] { return r.Double(); }), std::optional<double>(2.5));
  EXPECT_NO_THROW(r.Finish());
}

TEST(ByteCodec, TruncatedBytesAreAnErrorNamingTheSourceAndTheByte) {
  ByteWriter w;
  w.Int(7);
  w.String("hello");
  const std::string cut = w.bytes().substr(0, w.bytes().size() - 2);
  ByteReader r(cut, "job 3");
  EXPECT_EQ(r.Int(), 7);
  try {
    r.String();
    FAIL() << "a text longer than what is left was read";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("job 3: byte 16"));
    EXPECT_THAT(e.what(), HasSubstr("5 bytes, but only 3 are left"));
  }
  ByteReader empty("", "empty");
  EXPECT_THROW(empty.Double(), InputError);
}

TEST(ByteCodec, ValuesOutOfRangeAndLeftOverBytesAreErrors) {
  ByteWriter w;
  w.UInt(2);                  // not a flag
  w.Int(5);                   // not a Colour
  w.Int(-3);                  // outside [0, 10]
  w.UInt(uint64_t{1} << 60);  // a count of doubles that cannot be there
  ByteReader r(w.bytes(), "s");
  EXPECT_THROW(r.Bool(), InputError);
  EXPECT_THROW(r.EnumValue(Colour::kBlue), InputError);
  EXPECT_THROW(r.IntIn(0, 10), InputError);
  EXPECT_THROW(r.Doubles(), InputError);

  ByteWriter two;
  two.Int(1);
  two.Int(2);
  ByteReader partly(two.bytes(), "s");
  partly.Int();
  EXPECT_THROW(partly.Finish(), InputError);
}

TEST(ByteCodec, FingerprintIsFnv1a64) {
  EXPECT_EQ(Fingerprint(""), "cbf29ce484222325");
  EXPECT_EQ(Fingerprint("a"), "af63dc4c8601ec8c");
  EXPECT_NE(Fingerprint("seed 1"), Fingerprint("seed 2"));
}

}  // namespace
}  // namespace graspsynth
