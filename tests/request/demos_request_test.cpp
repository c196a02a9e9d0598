// Tests of the request of demos generate and calibrate (request/demos_request.hpp): its
// options are described once, optional ones keep the operator file's values, a value out of
// range names the option, and a config file sets them.

#include "request/demos_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

// The shipped operator with a seed, a trial count and one plan's own count of its own.
OperatorOptions FileOptions() {
  OperatorOptions options = ReadOperatorOptions(DefaultOperatorOptionsPath());
  options.seed = 17;
  options.trials_per_orientation = 4;
  options.plans[0].trials = 6;
  return options;
}

TEST(DemosRequest, EveryOptionIsWellDescribed) {
  ExpectWellDescribed(DemosGenerateOptions());
  ExpectWellDescribed(DemosCalibrateOptions());
}

TEST(DemosRequest, TheDefaultsKeepTheOperatorFilesValues) {
  const OperatorOptions options = ApplyToOperator(DemosRequest{}, FileOptions());
  EXPECT_EQ(options.seed, 17u);
  EXPECT_EQ(options.trials_per_orientation, 4);
  EXPECT_EQ(options.plans[0].trials, 6);
  EXPECT_TRUE(options.positions.empty());
  const DemosRequest r;
  EXPECT_EQ(r.iterations, 3);
  EXPECT_EQ(r.damping, 0.7);
}

TEST(DemosRequest, OptionsOverrideTheOperatorFile) {
  DemosRequest r;
  Apply(*FindOption(DemosGenerateOptions(), "seed"), Value(uint64_t{5}), "seed", &r);
  Apply(*FindOption(DemosGenerateOptions(), "trials_per_orientation"), Value(int64_t{2}),
        "trials_per_orientation", &r);
  r.x = "-0.3,-0.25";
  r.y = "0.9";
  const OperatorOptions options = ApplyToOperator(r, FileOptions());
  EXPECT_EQ(options.seed, 5u);
  EXPECT_EQ(options.trials_per_orientation, 2);
  EXPECT_EQ(options.plans[0].trials, 0);  // the same count everywhere
  EXPECT_EQ(options.positions.size(), 2u);
  // none (Python's None, JSON null) sets an optional option back to the file's.
  Apply(*FindOption(DemosGenerateOptions(), "seed"), Value(std::monostate{}), "seed", &r);
  EXPECT_FALSE(r.seed.has_value());
  r.y.clear();
  GS_EXPECT_THROW_WITH(ApplyToOperator(r, FileOptions()), InputError, "--x", "--y");
}

TEST(DemosRequest, AValueOutOfRangeIsAnInputErrorNamingTheOption) {
  DemosRequest r;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(DemosCalibrateOptions(), "damping"), Value(0.01), "--damping", &r),
      InputError, "--damping: must be [0.05, 1] (got 0.01)");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(DemosCalibrateOptions(), "trials_per_orientation"),
                             Value(int64_t{0}), "--trials-per-orientation", &r),
                       InputError, "--trials-per-orientation: must be >= 1 (got 0)");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(DemosGenerateOptions(), "x"), Value(std::string("0.1,west")), "--x", &r),
      InputError, "--x");
  EXPECT_EQ(FindOption(DemosGenerateOptions(), "damping"), nullptr);  // calibrate's alone
}

TEST(DemosRequest, AConfigFileSetsOptionsAndNullIsNone) {
  DemosRequest r;
  r.seed = 3;
  ApplyConfig(DemosGenerateOptions(),
              WriteConfig("demos.json", R"({"seed": null, "trials_per_orientation": 2})"), &r);
  EXPECT_FALSE(r.seed.has_value());
  EXPECT_EQ(r.trials_per_orientation, 2);
  GS_EXPECT_THROW_WITH(
      ApplyConfig(DemosGenerateOptions(), WriteConfig("bad.json", R"({"threads": null})"), &r),
      InputError, "field 'threads'");
}

}  // namespace
}  // namespace graspsynth::request
