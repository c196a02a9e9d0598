// Tests of common/field_list.hpp, field_codec.hpp and field_text.hpp on a small result: one
// field list drives the job bytes (every field, to the bit), the JSON (the fields naming a
// pointer) and the CSV (the fields naming a column, in column order).

#include "common/field_list.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "common/field_codec.hpp"
#include "common/field_text.hpp"

namespace graspsynth {

enum class Colour { kRed, kGreen };

const char* ToString(Colour c) { return c == Colour::kRed ? "red" : "green"; }

template <>
struct EnumRange<Colour> {
  static constexpr Colour kLast = Colour::kGreen;
};

struct Inner {
  double x = 0.0;
  std::array<double, 2> pair{};
};

template <class V, class Row>
requires SameStruct<Row, Inner>
void VisitFields(V& v, Row& r) {
  v(Field("x").Json("/x"), r.x);
  v(Field("pair"), r.pair);
}

struct Toy {
  double a = 0.0;
  std::optional<Eigen::Vector2d> at;
  std::string name;
  std::optional<Colour> colour;
  int count = 0;
  uint64_t seed = 0;
  bool flag = false;
  Inner inner;
  std::vector<Inner> inners;
  std::vector<double> values;
  double hidden = 0.0;
};

template <class V, class Row>
requires SameStruct<Row, Toy>
void VisitFields(V& v, Row& r) {
  v(Field("a").Json("/a").Csv(2), r.a);
  v(Field("at").Json("/at").OmitEmpty().Csv(0, "x,y").Shortest(), r.at);
  v(Field("name").Json("/group/name").Csv(1), r.name);
  v(Field("colour").Json("/group/colour").NullText("none").Csv(3), r.colour);
  v(Field("count").Json("/pair/0"), r.count);
  v(Field("seed").Json("/pair/1"), r.seed);
  v(Field("flag").Csv(4), r.flag);
  v(Field("inner").Json("/inner"), r.inner);
  v(Field("inners").Json("/inners"), r.inners);
  v(Field("values"), r.values);
  v(Field("hidden"), r.hidden);
}

// A pose, a quaternion, pairs of texts and a text left out of the JSON when empty.
struct Shapes {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  std::vector<std::pair<std::string, std::string>> extra;
  std::string note;
};

template <class V, class Row>
requires SameStruct<Row, Shapes>
void VisitFields(V& v, Row& r) {
  v(Field("q"), r.q);
  v(Field("pose"), r.pose);
  v(Field("extra"), r.extra);
  v(Field("note").Json("/note").OmitEmpty(), r.note);
}

namespace {

using nlohmann::json;

Toy FullToy() {
  Toy t;
  t.a = 0.1 + 0.2;
  t.at = Eigen::Vector2d(-0.3, 0.85);
  t.name = "a, \"quoted\" name";
  t.colour = Colour::kGreen;
  t.count = -7;
  t.seed = 0xFEDCBA9876543210ULL;
  t.flag = true;
  t.inner = {1.5, {2.5, -3.5}};
  t.inners = {{4.0, {5.0, 6.0}}, {7.0, {8.0, 9.0}}};
  t.values = {1e-300, -0.0};
  t.hidden = 42.0;
  return t;
}

TEST(FieldList, CountsAndVisitsOneField) {
  EXPECT_EQ(FieldCount<Toy>(), 11u);
  std::string name;
  VisitField(FullToy(), 2, [&](const Field& f, const auto&) { name = f.name; });
  EXPECT_EQ(name, "name");
}

TEST(FieldCodec, EveryFieldComesBackToTheBit) {
  const Toy t = FullToy();
  const std::string bytes = EncodeFields(t);
  const Toy back = DecodeFields<Toy>(bytes, "toy");
  EXPECT_EQ(EncodeFields(back), bytes);
  EXPECT_EQ(back.a, t.a);
  EXPECT_EQ(*back.at, *t.at);
  EXPECT_EQ(back.name, t.name);
  EXPECT_EQ(back.colour, Colour::kGreen);
  EXPECT_EQ(back.seed, t.seed);
  EXPECT_EQ(back.inners[1].pair[1], 9.0);
  EXPECT_TRUE(std::signbit(back.values[1]));
  EXPECT_EQ(back.hidden, 42.0);
  // an unset optional comes back unset.
  EXPECT_FALSE(DecodeFields<Toy>(EncodeFields(Toy{}), "toy").at.has_value());
}

TEST(FieldCodec, DamagedBytesAreAnInputError) {
  const std::string bytes = EncodeFields(FullToy());
  for (size_t n = 0; n < bytes.size(); n += 5) {
    EXPECT_THROW(DecodeFields<Toy>(bytes.substr(0, n), "cut"), InputError) << n;
  }
  EXPECT_THROW(DecodeFields<Toy>(bytes + "x", "longer"), InputError);
  // the colour is the 4th field: after a (8), at (8 + 16), name (8 + its characters), and its
  // own presence flag (8).
  std::string bad = bytes;
  bad[8 + 24 + 8 + FullToy().name.size() + 8] = 2;  // Colour has values 0 and 1 only
  EXPECT_THROW(DecodeFields<Toy>(bad, "bad colour"), InputError);
}

TEST(FieldCodec, QuaternionsPosesAndPairsComeBackToTheBit) {
  Shapes s;
  s.q = Eigen::Quaterniond(0.5, -0.5, 0.5 + 1e-16, 0.5);  // w x y z, not normalized
  s.pose.translate(Eigen::Vector3d(0.1, -0.2, 0.3))
      .rotate(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  s.extra = {{"key", "value"}, {"", "empty key"}};
  const Shapes back = DecodeFields<Shapes>(EncodeFields(s), "shapes");
  EXPECT_EQ(back.q.coeffs(), s.q.coeffs());
  EXPECT_EQ(back.pose.matrix(), s.pose.matrix());
  EXPECT_EQ(back.extra, s.extra);
  // w first: the old hand-written codecs' order.
  const std::string bytes = EncodeFields(s);
  EXPECT_EQ(DecodeFields<Shapes>(bytes, "shapes").q.w(), 0.5);
  EXPECT_EQ(bytes.substr(0, 8), EncodeFields(Inner{0.5, {}}).substr(0, 8));
}

TEST(FieldText, JsonHasTheFieldsThatNameAPointer) {
  const json j = FieldsJson<json>(FullToy());
  EXPECT_EQ(j["a"], 0.1 + 0.2);
  EXPECT_EQ(j["at"], json({-0.3, 0.85}));
  EXPECT_EQ(j["group"]["name"], "a, \"quoted\" name");
  EXPECT_EQ(j["group"]["colour"], "green");
  EXPECT_EQ(j["pair"], json({-7, 0xFEDCBA9876543210ULL}));
  EXPECT_EQ(j["inner"], json({{"x", 1.5}}));
  EXPECT_EQ(j["inners"][1]["x"], 7.0);
  EXPECT_FALSE(j.contains("flag") || j.contains("values") || j.contains("hidden"));
  // an empty optional: left out, or its null text.
  const json bare = FieldsJson<json>(Toy{});
  EXPECT_FALSE(bare.contains("at"));
  EXPECT_EQ(bare["group"]["colour"], "none");
  // a report's own form of a type.
  struct Forms {
    json operator()(const Inner& i) const { return i.x * 2; }
  };
  EXPECT_EQ(FieldsJson<json>(FullToy(), Forms{})["inner"], 3.0);
  // an empty text marked OmitEmpty is left out; a text that has something is there.
  Shapes shapes;
  EXPECT_FALSE(FieldsJson<json>(shapes).contains("note"));
  shapes.note = "n";
  EXPECT_EQ(FieldsJson<json>(shapes)["note"], "n");
}

TEST(FieldText, CsvHasTheColumnsInOrder) {
  Toy bare;
  bare.name = "plain";
  EXPECT_EQ(FieldsCsv(std::vector<Toy>{bare}), "name,a,colour,flag\nplain,0,none,0\n");
  EXPECT_EQ(FieldsCsv(std::vector<Toy>{FullToy(), bare}),
            "x,y,name,a,colour,flag\n"
            "-0.3,0.85,\"a, \"\"quoted\"\" name\",0.30000000000000004,green,1\n"
            "nan,nan,plain,0,none,0\n");
}

}  // namespace
}  // namespace graspsynth
