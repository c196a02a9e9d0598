// Tests of the request of analyze and Python's analyze_demonstrations
// (request/analyze_request.hpp): its options are described once, with the library's defaults,
// are checked naming the option, are read from a config file, and map onto the library's
// options over the scene's grasp region.

#include "request/analyze_request.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/request/request_test_utils.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::request {
namespace {

GraspRegionModel SceneRegion() {
  GraspRegionModel region;
  region.shape = GraspRegionModel::Shape::kCylinder;
  region.radius = 0.41;
  region.height = 1.0;
  return region;
}

TEST(AnalyzeRequest, EveryOptionIsWellDescribed) { ExpectWellDescribed(AnalyzeOptions()); }

TEST(AnalyzeRequest, TheDefaultsAreTheLibrarysOverTheScenesRegion) {
  const AnalysisOptions options = ToAnalysisOptions(AnalyzeRequest{}, SceneRegion());
  const AnalysisOptions library;
  EXPECT_EQ(options.segmentation.success_lift, library.segmentation.success_lift);
  EXPECT_EQ(options.segmentation.region.radius, 0.41);
  EXPECT_EQ(options.segmentation.region.height, 1.0);
  EXPECT_EQ(options.segmentation.region.shape, GraspRegionModel::Shape::kCylinder);
  EXPECT_EQ(options.line.loss, library.line.loss);
  EXPECT_EQ(options.line.loss_scale, library.line.loss_scale);
  EXPECT_EQ(options.line_points, library.line_points);
}

TEST(AnalyzeRequest, OptionsMapOntoTheLibrarys) {
  AnalyzeRequest r;
  r.region = "sphere";
  r.region_radius = 0.3;
  r.robust_loss = "cauchy";
  r.loss_scale = 0.02;
  r.line_points = "trials";
  const AnalysisOptions options = ToAnalysisOptions(r, SceneRegion());
  EXPECT_EQ(options.segmentation.region.shape, GraspRegionModel::Shape::kSphere);
  EXPECT_EQ(options.segmentation.region.radius, 0.3);
  EXPECT_EQ(options.segmentation.region.height, 1.0);
  EXPECT_EQ(options.line.loss, LineLoss::kCauchy);
  EXPECT_EQ(options.line.loss_scale, 0.02);
  EXPECT_EQ(options.line_points, LinePoints::kTrials);
}

TEST(AnalyzeRequest, AValueOutOfRangeIsAnInputErrorNamingTheOption) {
  const OptionList<AnalyzeRequest>& options = AnalyzeOptions();
  AnalyzeRequest r;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "region"), Value(std::string("cube")), "--region", &r), InputError,
      "--region: 'cube' is not one of cylinder, sphere");
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(options, "robust_loss"), Value(std::string("l1")), "--robust-loss", &r),
      InputError, "--robust-loss: 'l1' is not one of none, huber, cauchy");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "loss_scale"), Value(0.0), "--loss-scale", &r),
                       InputError, "--loss-scale: must be > 0 (got 0)");
  GS_EXPECT_THROW_WITH(Apply(*FindOption(options, "success_lift"), Value(-0.1), "success_lift", &r),
                       InputError, "success_lift: must be >= 0 (got -0.1)");
}

TEST(AnalyzeRequest, AConfigFileSetsOptionsByName) {
  AnalyzeRequest r;
  ApplyConfig(AnalyzeOptions(),
              WriteConfig("analyze.json", R"({"robust_loss": "huber", "region_radius": 0.35})"),
              &r);
  EXPECT_EQ(r.robust_loss, "huber");
  EXPECT_EQ(r.region_radius, 0.35);
  GS_EXPECT_THROW_WITH(
      ApplyConfig(AnalyzeOptions(), WriteConfig("bad.json", R"({"line_points": "all"})"), &r),
      InputError, "field 'line_points'", "'all' is not one of means, trials");
}

// Python's segment and fit_wrist_line take analyze's options of the same name, described once.
TEST(AnalyzeRequest, SegmentAndTheLineFitTakeAnalyzesOptions) {
  ExpectWellDescribed(SegmentOptions());
  ExpectWellDescribed(WristLineRequestOptions());
  const auto info = [](const auto& options, const char* name) {
    const auto* o = FindOption(options, name);
    EXPECT_NE(o, nullptr) << name;
    return o ? o->info.help : std::string();
  };
  EXPECT_EQ(info(SegmentOptions(), "success_lift"), info(AnalyzeOptions(), "success_lift"));
  EXPECT_EQ(info(WristLineRequestOptions(), "robust_loss"), info(AnalyzeOptions(), "robust_loss"));
  EXPECT_EQ(info(WristLineRequestOptions(), "loss_scale"), info(AnalyzeOptions(), "loss_scale"));

  const SegmentationOptions segmentation =
      ToSegmentationOptions(SegmentRequest{0.07}, SceneRegion());
  EXPECT_EQ(segmentation.success_lift, 0.07);
  EXPECT_EQ(segmentation.region.radius, 0.41);
  EXPECT_EQ(ToSegmentationOptions(SegmentRequest{}, SceneRegion()).success_lift,
            SegmentationOptions{}.success_lift);
  const WristLineOptions line = ToWristLineOptions(WristLineRequest{"huber", 0.03});
  EXPECT_EQ(line.loss, LineLoss::kHuber);
  EXPECT_EQ(line.loss_scale, 0.03);
  EXPECT_EQ(ToWristLineOptions(WristLineRequest{}).loss, WristLineOptions{}.loss);
  WristLineRequest r;
  GS_EXPECT_THROW_WITH(
      Apply(*FindOption(WristLineRequestOptions(), "loss_scale"), Value(-1.0), "loss_scale", &r),
      InputError, "loss_scale: must be > 0 (got -1)");
}

}  // namespace
}  // namespace graspsynth::request
