#include "common/json_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::ElementsAre;

JsonReader Doc(std::string_view text) { return JsonReader::Parse(text, "in.json"); }

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(JsonReader, ReadsTypedFields) {
  const JsonReader r = Doc(
      R"({"x": 1.5, "n": -3, "u": 7, "b": true, "s": "hi", "v": [1, 2, 3],
          "q": [1, 0, 0, 0], "o": {"y": 2}})");
  EXPECT_EQ(r.Number("x"), 1.5);
  EXPECT_EQ(r.NumberIn("x", 1.0, 2.0), 1.5);
  EXPECT_EQ(r.PositiveNumber("x"), 1.5);
  EXPECT_EQ(r.Integer("n", -5, 5), -3);
  EXPECT_EQ(r.Unsigned("u"), 7u);
  EXPECT_TRUE(r.Bool("b"));
  EXPECT_EQ(r.String("s"), "hi");
  EXPECT_EQ(r.Vector3("v"), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(r.Quaternion("q").coeffs(), Eigen::Quaterniond::Identity().coeffs());
  EXPECT_EQ(r.Object("o").Number("y"), 2.0);
  EXPECT_EQ(r.Object("o").path(), "o");
  EXPECT_TRUE(r.Has("x"));
  EXPECT_FALSE(r.Has("missing"));
  EXPECT_THAT(r.Keys(), ElementsAre("x", "n", "u", "b", "s", "v", "q", "o"));
}

TEST(JsonReader, OptionalFieldsAreEmptyWhenAbsent) {
  const JsonReader r = Doc(R"({"x": 2})");
  EXPECT_EQ(r.OptionalNumber("x"), 2.0);
  EXPECT_EQ(r.OptionalNumber("y"), std::nullopt);
  EXPECT_FALSE(r.OptionalField("y").has_value());
  EXPECT_FALSE(r.Field("y").present());
  EXPECT_TRUE(r.Field("x").present());
}

TEST(JsonReader, ErrorNamesSourceFieldPathValueAndExpectation) {
  const JsonReader r =
      Doc(R"({"entries": [{}, {}, {}, {"grasp": {"wrist": {"q": [1, 0, "a"]}}}]})");
  const std::vector<JsonReader> entries = r.Array("entries");
  ASSERT_EQ(entries.size(), 4u);
  const JsonReader q = entries[3].Object("grasp").Object("wrist").Array("q")[2];
  EXPECT_EQ(q.path(), "entries[3].grasp.wrist.q[2]");
  EXPECT_EQ(ErrorOf([&] { q.AsNumber(); }),
            "in.json: field 'entries[3].grasp.wrist.q[2]': expected a finite number, found \"a\"");
}

TEST(JsonReader, MissingFieldIsFoundNothing) {
  const JsonReader r = Doc(R"({"a": {"b": 1}})");
  EXPECT_EQ(ErrorOf([&] { r.Object("a").Number("c"); }),
            "in.json: field 'a.c': expected a finite number, found nothing");
  EXPECT_EQ(ErrorOf([&] { r.String("z"); }),
            "in.json: field 'z': expected a string, found nothing");
}

TEST(JsonReader, RootErrorsNameTheDocument) {
  EXPECT_EQ(ErrorOf([] { Doc("[1, 2]").Number("x"); }),
            "in.json: the document: expected an object, found [1,2]");
}

TEST(JsonReader, RejectsEachWrongKind) {
  const JsonReader r =
      Doc(R"({"s": "x", "n": 1.5, "neg": -1, "big": 18446744073709551615, "zero": 0, "arr": [1]})");
  EXPECT_THAT(ErrorOf([&] { r.Number("s"); }), ::testing::HasSubstr("expected a finite number"));
  EXPECT_EQ(ErrorOf([&] { r.NumberIn("n", 0, 1); }),
            "in.json: field 'n': expected a number in [0, 1], found 1.5");
  EXPECT_EQ(ErrorOf([&] { r.PositiveNumber("zero"); }),
            "in.json: field 'zero': expected a finite number > 0, found 0");
  EXPECT_EQ(ErrorOf([&] { r.Integer("n", 0, 9); }),
            "in.json: field 'n': expected an integer in [0, 9], found 1.5");
  EXPECT_EQ(ErrorOf([&] { r.Integer("neg", 0, 9); }),
            "in.json: field 'neg': expected an integer in [0, 9], found -1");
  EXPECT_THAT(ErrorOf([&] { r.Integer("big", 0, 9); }),
              ::testing::HasSubstr("found 18446744073709551615"));
  EXPECT_EQ(r.Unsigned("big"), 18446744073709551615ull);
  EXPECT_EQ(ErrorOf([&] { r.Unsigned("neg"); }),
            "in.json: field 'neg': expected a non-negative integer, found -1");
  EXPECT_EQ(ErrorOf([&] { r.Bool("zero"); }),
            "in.json: field 'zero': expected true or false, found 0");
  EXPECT_EQ(ErrorOf([&] { r.String("n"); }), "in.json: field 'n': expected a string, found 1.5");
  EXPECT_EQ(ErrorOf([&] { r.Array("n"); }), "in.json: field 'n': expected an array, found 1.5");
  EXPECT_EQ(ErrorOf([&] { r.Object("arr"); }),
            "in.json: field 'arr': expected an object, found [1]");
  EXPECT_EQ(ErrorOf([&] { r.Vector3("arr"); }),
            "in.json: field 'arr': expected an array of 3 finite numbers, found [1]");
  EXPECT_EQ(ErrorOf([&] { r.Field("arr").Field("x"); }),
            "in.json: field 'arr': expected an object, found [1]");
}

TEST(JsonReader, BoundedNumbersNameTheElement) {
  const JsonReader r = Doc(R"({"v": [0.5, 2.0]})");
  EXPECT_EQ(r.Numbers("v", 2, 0.0, 3.0), Eigen::Vector2d(0.5, 2.0));
  EXPECT_EQ(ErrorOf([&] { r.Numbers("v", 2, 0.0, 1.0); }),
            "in.json: field 'v[1]': expected a number in [0, 1], found 2.0");
}

TEST(JsonReader, NonFiniteTokensAreNamedByTheirField) {
  const JsonReader r = Doc(R"({"a": [1, NaN], "b": -Infinity, "s": "NaN"})");
  EXPECT_EQ(ErrorOf([&] { r.Numbers("a", 2); }),
            "in.json: field 'a[1]': expected a finite number, found NaN");
  EXPECT_EQ(ErrorOf([&] { r.Number("b"); }),
            "in.json: field 'b': expected a finite number, found -Infinity");
  EXPECT_EQ(ErrorOf([&] { r.String("b"); }),
            "in.json: field 'b': expected a string, found -Infinity");
  // a string that merely spells NaN stays a string.
  EXPECT_EQ(r.String("s"), "NaN");
}

TEST(JsonReader, UnitQuaternionChecksTheNorm) {
  const JsonReader r = Doc(R"({"q": [0.6, 0.8, 0, 0], "bad": [1, 1, 0, 0]})");
  const Eigen::Quaterniond q = r.UnitQuaternion("q", 1e-6);
  EXPECT_EQ(q.w(), 0.6);
  EXPECT_EQ(q.x(), 0.8);
  EXPECT_THAT(
      ErrorOf([&] { r.UnitQuaternion("bad", 1e-6); }),
      ::testing::AllOf(::testing::HasSubstr("in.json: field 'bad': expected a unit quaternion"),
                       ::testing::HasSubstr("found [1,1,0,0]")));
}

TEST(JsonReader, ExpectStringAndUnknownKeys) {
  const JsonReader r = Doc(R"({"format": "x/2", "extra": 1})");
  EXPECT_EQ(ErrorOf([&] { r.ExpectString("format", "x/1"); }),
            "in.json: field 'format': expected \"x/1\", found \"x/2\"");
  EXPECT_NO_THROW(r.ExpectString("format", "x/2"));
  EXPECT_EQ(ErrorOf([&] { r.RejectUnknownKeys({"format"}); }),
            "in.json: field 'extra': expected only the fields format here, found 1");
  EXPECT_NO_THROW(r.RejectUnknownKeys({"format", "extra"}));
}

TEST(JsonReader, LongValuesAreShortened) {
  const JsonReader r = Doc(R"({"s": [1111111111, 2222222222, 3333333333, 4444444444, 5555555555,
                                     6666666666, 7777777777]})");
  const std::string error = ErrorOf([&] { r.Number("s"); });
  EXPECT_THAT(error, ::testing::EndsWith("..."));
  EXPECT_LT(error.size(), 140u);
}

TEST(JsonReader, ParseErrorsNameTheSourceAndLine) {
  EXPECT_EQ(ErrorOf([] { Doc("{\"a\": \n [1,}"); }),
            "in.json: not valid JSON: parse error at line 2, column 5: syntax error while parsing "
            "value - unexpected '}'; expected '[', '{', or a literal");
  EXPECT_THAT(ErrorOf([] { Doc("{\"a\": 1e999}"); }),
              ::testing::AllOf(::testing::HasSubstr("in.json: not valid JSON"),
                               ::testing::HasSubstr("1e999")));
}

TEST(JsonReader, LoadReadsAFileAndNamesIt) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "graspsynth_json_reader_test.json";
  {
    std::ofstream out(path);
    out << R"({"x": "y"})";
  }
  const JsonReader r = JsonReader::Load(path);
  EXPECT_EQ(r.source(), path.string());
  EXPECT_EQ(ErrorOf([&] { r.Number("x"); }),
            path.string() + ": field 'x': expected a finite number, found \"y\"");
  std::filesystem::remove(path);
  EXPECT_THAT(ErrorOf([&] { JsonReader::Load(path); }),
              ::testing::HasSubstr("cannot read JSON file '" + path.string() + "': no such file"));
}

}  // namespace
}  // namespace graspsynth
