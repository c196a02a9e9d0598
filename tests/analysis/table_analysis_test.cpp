// Tests of Table I: polar means of pre-grasp and grasp positions per orientation.

#include "analysis/table_analysis.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::MakeTrial;
using testing::Polar;
using testing::TrialSpec;

TEST(TableAnalysis, PolarMeanOfExactData) {
  const Eigen::Vector2d c = Polar(0.4, -60.0);
  const PolarMean m =
      ComputePolarMean({c + Eigen::Vector2d(0.01, 0.0), c, c - Eigen::Vector2d(0.01, 0.0)});
  EXPECT_TRUE(testing::MatricesNear(m.mean_xy, c, 1e-15));
  EXPECT_NEAR(m.d, 0.4, 1e-15);
  EXPECT_NEAR(m.eta_deg, -60.0, 1e-12);
  EXPECT_NEAR(m.std_xy.x(), 0.01, 1e-15);  // sample std: sqrt((1e-4 + 1e-4) / 2)
  EXPECT_NEAR(m.std_xy.y(), 0.0, 1e-15);
  EXPECT_GT(m.std_d, 0.0);
  EXPECT_GT(m.std_eta_deg, 0.0);

  const PolarMean one = ComputePolarMean({Polar(0.3, 120.0)});
  EXPECT_NEAR(one.d, 0.3, 1e-15);
  EXPECT_NEAR(one.eta_deg, 120.0, 1e-12);
  EXPECT_EQ(one.std_d, 0.0);
  EXPECT_EQ(one.std_eta_deg, 0.0);
}

TEST(TableAnalysis, AveragesVectorsNotPolarCoordinates) {
  // the mean of (1, 0) and (0, 1) is (0.5, 0.5): d = 0.7071, not the mean distance 1.
  const PolarMean m = ComputePolarMean({Polar(1.0, 0.0), Polar(1.0, 90.0)});
  EXPECT_NEAR(m.d, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(m.eta_deg, 45.0, 1e-12);
  EXPECT_NEAR(m.std_d, 0.0, 1e-15);
  EXPECT_NEAR(m.std_eta_deg, std::sqrt(2.0 * 45.0 * 45.0), 1e-9);
}

TEST(TableAnalysis, AnglesAcrossPlusMinus180DoNotWrap) {
  const PolarMean m = ComputePolarMean({Polar(0.3, 179.0), Polar(0.3, -179.0)});
  EXPECT_NEAR(std::abs(m.eta_deg), 180.0, 1e-9);
  EXPECT_NEAR(m.std_eta_deg, std::sqrt(2.0), 1e-9);  // deviations +-1 deg, n - 1 = 1
}

TEST(TableAnalysis, GroupsSuccessfulTrialsByOrientationAndSkipsTheRest) {
  SegmentationOptions options;
  std::vector<SegmentedTrial> trials;
  TrialSpec spec;
  spec.theta_deg = 40.0;
  spec.pregrasp_xy = Polar(0.4, -66.0);
  spec.grasp_xy = Polar(0.358, -71.1) + Eigen::Vector2d(0.003, -0.002);
  spec.trial = "40a";
  trials.push_back(Segment(MakeTrial(spec), options));
  spec.grasp_xy = Polar(0.358, -71.1) - Eigen::Vector2d(0.003, -0.002);
  spec.trial = "40b";
  trials.push_back(Segment(MakeTrial(spec), options));
  spec.theta_deg = 20.0;
  spec.pregrasp_xy = Polar(0.405, -71.5);
  spec.grasp_xy = Polar(0.378, -75.3);
  spec.trial = "20a";
  trials.push_back(Segment(MakeTrial(spec), options));
  spec.lift = 0.0;  // dropped the object
  spec.trial = "20dropped";
  trials.push_back(Segment(MakeTrial(spec), options));
  spec.lift = 0.1;
  spec.pregrasp_xy = Polar(0.6, -70.0);  // never inside the region
  spec.grasp_xy = Polar(0.5, -70.0);
  spec.trial = "20outside";
  trials.push_back(Segment(MakeTrial(spec), options));

  const TableAnalysis table = AnalyzeTable(trials);
  EXPECT_EQ(table.trials, 5);
  EXPECT_EQ(table.used, 3);
  ASSERT_EQ(table.unsuccessful.size(), 1u);
  EXPECT_EQ(table.unsuccessful[0].file, "trial_20dropped.csv");
  EXPECT_THAT(table.unsuccessful[0].reason, HasSubstr("unsuccessful"));
  ASSERT_EQ(table.unsegmentable.size(), 1u);
  EXPECT_EQ(table.unsegmentable[0].file, "trial_20outside.csv");
  EXPECT_THAT(table.unsegmentable[0].reason, HasSubstr("never enters"));

  ASSERT_EQ(table.orientations.size(), 2u);
  const OrientationStats& r20 = table.orientations[0];
  const OrientationStats& r40 = table.orientations[1];
  EXPECT_EQ(r20.theta_deg, 20.0);
  EXPECT_EQ(r20.n, 1);
  EXPECT_NEAR(r20.pregrasp.d, 0.405, 1e-12);
  EXPECT_NEAR(r20.pregrasp.eta_deg, -71.5, 1e-9);
  EXPECT_NEAR(r20.grasp.d, 0.378, 1e-12);
  EXPECT_NEAR(r20.grasp.eta_deg, -75.3, 1e-9);
  EXPECT_EQ(r40.theta_deg, 40.0);
  EXPECT_EQ(r40.n, 2);
  EXPECT_EQ(r40.sources, (std::vector<std::string>{"trial_40a.csv", "trial_40b.csv"}));
  EXPECT_NEAR(r40.pregrasp.d, 0.4, 1e-12);
  EXPECT_NEAR(r40.pregrasp.eta_deg, -66.0, 1e-9);
  EXPECT_NEAR(r40.grasp.d, 0.358, 1e-12);
  EXPECT_NEAR(r40.grasp.eta_deg, -71.1, 1e-9);
  EXPECT_NEAR(r40.grasp.std_xy.x(), std::sqrt(2.0) * 0.003, 1e-12);
  EXPECT_NEAR(r40.grasp.std_xy.y(), std::sqrt(2.0) * 0.002, 1e-12);
  ASSERT_EQ(r40.grasp_points.size(), 2u);
  EXPECT_TRUE(testing::MatricesNear(r40.grasp_points[0],
                                    Polar(0.358, -71.1) + Eigen::Vector2d(0.003, -0.002), 1e-12));
}

TEST(TableAnalysis, EmptyInputGivesAnEmptyTable) {
  const TableAnalysis table = AnalyzeTable({});
  EXPECT_TRUE(table.orientations.empty());
  EXPECT_EQ(table.trials, 0);
  EXPECT_EQ(table.used, 0);
}

TEST(TableAnalysis, ALogAtAMovedPlacementIsAnalysedRelativeToItsOwnObjectCentre) {
  // the same trial with the object 0.1 m along x and 0.05 m along y from the scene's centre:
  // the pre-grasp is still the first sample inside the cylinder around its own object, and the
  // polar figures are the same.
  SegmentationOptions options;
  TrialSpec spec;
  spec.theta_deg = 40.0;
  spec.pregrasp_xy = Polar(0.4, -66.0);
  spec.grasp_xy = Polar(0.358, -71.1);
  const SegmentedTrial at_centre = Segment(MakeTrial(spec), options);
  spec.p_WO += Eigen::Vector3d(0.1, 0.05, 0.0);
  spec.trial = "moved";
  const SegmentedTrial moved = Segment(MakeTrial(spec), options);
  ASSERT_TRUE(moved.ok()) << moved.message;
  EXPECT_EQ(moved.pregrasp, at_centre.pregrasp);
  EXPECT_EQ(moved.grasp, at_centre.grasp);
  EXPECT_TRUE(testing::MatricesNear(moved.motion.p_WO, spec.p_WO, 0.0));
  const TableAnalysis a = AnalyzeTable({at_centre});
  const TableAnalysis b = AnalyzeTable({moved});
  ASSERT_EQ(b.orientations.size(), 1u);
  EXPECT_NEAR(b.orientations[0].grasp.d, 0.358, 1e-12);
  EXPECT_NEAR(b.orientations[0].grasp.eta_deg, -71.1, 1e-9);
  EXPECT_NEAR(b.orientations[0].pregrasp.d, a.orientations[0].pregrasp.d, 1e-12);
  EXPECT_NEAR(b.orientations[0].pregrasp.eta_deg, a.orientations[0].pregrasp.eta_deg, 1e-9);
}

}  // namespace
}  // namespace graspsynth
