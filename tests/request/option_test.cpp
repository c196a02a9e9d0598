// Tests of request/option.hpp: each kind of option read from command-line text, from JSON and
// checked against its range and choices, with messages that name the option as its front end
// spells it; the config file; the names the front ends show.

#include "request/option.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <optional>

#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth::request {
namespace {

struct Inner {
  double share = 0.5;
};

// A request with one option of each kind, one of them inside a nested struct.
struct Toy {
  bool fast = false;
  bool check = true;
  int count = 3;
  uint64_t seed = 7;
  std::string mode = "a";
  std::vector<std::string> names = {"x"};
  std::vector<double> pair = {1.0, 2.0};
  Inner inner;
};

OptionInfo Info(const char* name, OptionKind kind) { return MakeInfo(name, kind, ""); }

const OptionList<Toy>& ToyOptions() {
  static const OptionList<Toy> options = [] {
    OptionList<Toy> list;
    list.push_back(
        FieldOption<Toy>(Info("fast", OptionKind::kBool), [](Toy& t) -> bool& { return t.fast; }));
    list.push_back(FieldOption<Toy>(Info("check", OptionKind::kBool),
                                    [](Toy& t) -> bool& { return t.check; }));
    OptionInfo count = Info("count", OptionKind::kInt);
    count.lo = 0;
    count.hi = 10;
    list.push_back(FieldOption<Toy>(count, [](Toy& t) -> int& { return t.count; }));
    list.push_back(FieldOption<Toy>(Info("seed", OptionKind::kUnsigned),
                                    [](Toy& t) -> uint64_t& { return t.seed; }));
    OptionInfo mode = Info("mode", OptionKind::kText);
    mode.choices = {"a", "b"};
    list.push_back(FieldOption<Toy>(mode, [](Toy& t) -> std::string& { return t.mode; }));
    list.push_back(FieldOption<Toy>(Info("names", OptionKind::kTextList),
                                    [](Toy& t) -> std::vector<std::string>& { return t.names; }));
    list.push_back(FieldOption<Toy>(Info("pair", OptionKind::kNumberPair),
                                    [](Toy& t) -> std::vector<double>& { return t.pair; }));
    OptionInfo share = Info("share", OptionKind::kNumber);
    share.lo = 0.0;
    share.hi = 1.0;
    share.hi_open = true;
    list.push_back(FieldOption<Toy>(share, [](Toy& t) -> double& { return t.inner.share; }));
    return list;
  }();
  return options;
}

const Option<Toy>& Named(const char* name) { return *FindOption(ToyOptions(), name); }

TEST(Option, FlagsAreTheNamesInKebabCaseAndABoolOnByDefaultIsNegated) {
  const Toy defaults;
  EXPECT_EQ(Named("fast").info.Flag(Named("fast").get(defaults)), "--fast");
  EXPECT_EQ(Named("check").info.Flag(Named("check").get(defaults)), "--no-check");
  EXPECT_EQ(Named("share").info.Flag(Named("share").get(defaults)), "--share");
  OptionInfo two_words = Info("min_robustness", OptionKind::kNumber);
  EXPECT_EQ(two_words.Flag(0.8), "--min-robustness");
  OptionInfo on_off = Info("physics", OptionKind::kBool);
  on_off.on_off = true;
  EXPECT_EQ(on_off.Flag(true), "--physics");
  EXPECT_EQ(on_off.Placeholder(), "on|off");
  EXPECT_EQ(Named("mode").info.Placeholder(), "a|b");
  EXPECT_EQ(Named("pair").info.Placeholder(), "MIN MAX");
}

TEST(Option, CommandLineTextOfEveryKind) {
  EXPECT_EQ(std::get<bool>(ParseText(Named("fast").info, "on", "--fast")), true);
  EXPECT_EQ(std::get<int64_t>(ParseText(Named("count").info, "10", "--count")), 10);
  EXPECT_EQ(std::get<uint64_t>(ParseText(Named("seed").info, "18446744073709551615", "--seed")),
            UINT64_MAX);
  EXPECT_EQ(std::get<std::string>(ParseText(Named("mode").info, "b", "--mode")), "b");
  EXPECT_EQ(std::get<std::vector<std::string>>(ParseText(Named("names").info, "p,q", "--names")),
            (std::vector<std::string>{"p", "q"}));
  EXPECT_EQ(std::get<std::vector<double>>(ParseText(Named("pair").info, "0.5 2", "--pair")),
            (std::vector<double>{0.5, 2.0}));
  EXPECT_EQ(std::get<double>(ParseText(Named("share").info, "0.25", "--share")), 0.25);
}

TEST(Option, AValueOutOfItsRangeOrChoicesIsRefusedNamingTheOption) {
  GS_EXPECT_THROW_WITH(ParseText(Named("count").info, "11", "--count"), InputError,
                       "--count: must be [0, 10] (got 11)");
  GS_EXPECT_THROW_WITH(ParseText(Named("count").info, "4294967296", "--count"), InputError,
                       "--count: is too large (got 4294967296)");
  GS_EXPECT_THROW_WITH(ParseText(Named("count").info, "2.5", "--count"), InputError,
                       "--count: '2.5' is not an integer");
  GS_EXPECT_THROW_WITH(ParseText(Named("seed").info, "-1", "--seed"), InputError,
                       "--seed: '-1' is not an integer >= 0");
  GS_EXPECT_THROW_WITH(ParseText(Named("share").info, "1", "--share"), InputError,
                       "--share: must be [0, 1) (got 1)");
  GS_EXPECT_THROW_WITH(ParseText(Named("share").info, "nan", "--share"), InputError,
                       "'nan' is not a finite number");
  GS_EXPECT_THROW_WITH(ParseText(Named("mode").info, "c", "--mode"), InputError,
                       "--mode: 'c' is not one of a, b");
  GS_EXPECT_THROW_WITH(ParseText(Named("pair").info, "2 1", "--pair"), InputError,
                       "needs 0 < MIN <= MAX (got 2 1)");
  GS_EXPECT_THROW_WITH(ParseText(Named("fast").info, "yes", "--fast"), InputError,
                       "'yes' is neither on nor off");
}

TEST(Option, ApplyChecksAndWritesThroughNestedOptions) {
  Toy toy;
  Apply(Named("share"), Value(0.75), "share", &toy);
  EXPECT_EQ(toy.inner.share, 0.75);
  GS_EXPECT_THROW_WITH(Apply(Named("share"), Value(-0.1), "share", &toy), InputError,
                       "share: must be [0, 1) (got -0.1)");
  EXPECT_EQ(toy.inner.share, 0.75);  // a refused value leaves the request as it was
  GS_EXPECT_THROW_WITH(Apply(Named("count"), Value(std::string("3")), "count", &toy), InputError,
                       "count: needs an integer");
}

TEST(Option, ShowValueIsWhatTheHelpAndPythonShow) {
  const Toy defaults;
  EXPECT_EQ(ShowValue(Named("share").info, Named("share").get(defaults)), "0.5");
  EXPECT_EQ(ShowValue(Named("names").info, Value(std::vector<std::string>{"a", "b"})), "a,b");
  EXPECT_EQ(ShowValue(Named("pair").info, Named("pair").get(defaults)), "1 2");
  EXPECT_EQ(ShowValue(Named("fast").info, Value(true)), "true");
}

// An optional option: none (std::monostate) is its default and a value like any other; a
// plain option refuses none.
TEST(Option, AnOptionalOptionHoldsNoneOrAValueInItsRange) {
  struct Maybe {
    std::optional<int> count;
    std::optional<uint64_t> seed;
  };
  const Option<Maybe> count =
      OptionalFieldOption<Maybe>(WithRange(Info("count", OptionKind::kInt), 1),
                                 [](Maybe& m) -> std::optional<int>& { return m.count; });
  const Option<Maybe> seed =
      OptionalFieldOption<Maybe>(Info("seed", OptionKind::kUnsigned),
                                 [](Maybe& m) -> std::optional<uint64_t>& { return m.seed; });
  EXPECT_TRUE(count.info.optional);
  Maybe m;
  EXPECT_TRUE(std::holds_alternative<std::monostate>(count.get(m)));
  EXPECT_EQ(CheckValue(count.info, count.get(m)), "");
  EXPECT_EQ(ShowValue(count.info, count.get(m)), "");
  Apply(count, ParseText(count.info, "4", "--count"), "--count", &m);
  Apply(seed, ParseText(seed.info, "9", "--seed"), "--seed", &m);
  EXPECT_EQ(m.count, 4);
  EXPECT_EQ(m.seed, 9u);
  EXPECT_EQ(ShowValue(count.info, count.get(m)), "4");
  GS_EXPECT_THROW_WITH(Apply(count, Value(int64_t{0}), "--count", &m), InputError,
                       "--count: must be >= 1 (got 0)");
  Apply(count, Value(std::monostate{}), "count", &m);
  EXPECT_FALSE(m.count.has_value());
  EXPECT_EQ(CheckValue(Info("plain", OptionKind::kInt), Value(std::monostate{})), "needs a value");
}

TEST(Option, TheNearestNameOfAMistypedOne) {
  const std::vector<std::string> names = {"perturb", "seed", "threads", "min_robustness"};
  EXPECT_EQ(NearestName(names, "pertub"), "perturb");
  EXPECT_EQ(NearestName(names, "thread"), "threads");
  EXPECT_EQ(NearestName(names, "colour"), "");
}

class ConfigFile : public ::testing::Test {
 protected:
  std::filesystem::path Write(const std::string& text) {
    const std::filesystem::path path = folder_.path() / "options.json";
    std::ofstream(path) << text;
    return path;
  }
  testing::TestFolder folder_;
};

TEST_F(ConfigFile, SetsTheOptionsItNamesAndLeavesTheOthers) {
  Toy toy;
  ApplyConfig(ToyOptions(),
              Write(R"({"format": "graspsynth-options/1", "count": 5, "names": ["p", "q"],
                        "pair": [0.5, 4], "share": 0.125, "check": false})"),
              &toy);
  EXPECT_EQ(toy.count, 5);
  EXPECT_EQ(toy.names, (std::vector<std::string>{"p", "q"}));
  EXPECT_EQ(toy.pair, (std::vector<double>{0.5, 4.0}));
  EXPECT_EQ(toy.inner.share, 0.125);
  EXPECT_FALSE(toy.check);
  EXPECT_EQ(toy.mode, "a");
  EXPECT_EQ(toy.seed, 7u);
}

TEST_F(ConfigFile, RefusesAnUnknownKeyWithTheNearestOptionAndABadValueWithItsField) {
  Toy toy;
  const std::filesystem::path unknown = Write(R"({"cout": 5})");
  GS_EXPECT_THROW_WITH(ApplyConfig(ToyOptions(), unknown, &toy), InputError, unknown.string(),
                       "field 'cout' is not an option", "did you mean 'count'?");
  const std::filesystem::path range = Write(R"({"count": 50})");
  GS_EXPECT_THROW_WITH(ApplyConfig(ToyOptions(), range, &toy), InputError, range.string(),
                       "field 'count'");
  const std::filesystem::path kind = Write(R"({"share": "half"})");
  GS_EXPECT_THROW_WITH(ApplyConfig(ToyOptions(), kind, &toy), InputError, "field 'share'",
                       "\"half\"");
  const std::filesystem::path format = Write(R"({"format": "graspsynth-grasp/1"})");
  GS_EXPECT_THROW_WITH(ApplyConfig(ToyOptions(), format, &toy), InputError, "graspsynth-options/1");
  GS_EXPECT_THROW_WITH(ApplyConfig(ToyOptions(), Write("[1, 2]"), &toy), InputError,
                       "expected an object");
  EXPECT_EQ(toy.count, 3);
}

}  // namespace
}  // namespace graspsynth::request
