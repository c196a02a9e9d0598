// Tests of the segmentation of demonstrations into reach, grasp and lift.

#include "learning_data/segmentation.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::MakeTrial;
using testing::Polar;
using testing::TrialSpec;

SegmentationOptions Cylinder(double radius, double height = 1.0) {
  SegmentationOptions o;
  o.region.shape = GraspRegionModel::Shape::kCylinder;
  o.region.radius = radius;
  o.region.height = height;
  return o;
}

SegmentationOptions Sphere(double radius) {
  SegmentationOptions o;
  o.region.shape = GraspRegionModel::Shape::kSphere;
  o.region.radius = radius;
  return o;
}

TEST(Segmentation, DefaultsAreThoseOfTheScene) {
  const SegmentationOptions o;
  EXPECT_EQ(o.region.shape, GraspRegionModel::Shape::kCylinder);
  EXPECT_EQ(o.region.radius, 0.41);
  EXPECT_EQ(o.region.height, 1.0);
  EXPECT_EQ(o.success_lift, 0.05);
  EXPECT_TRUE(o.IsValid(nullptr));
}

TEST(Segmentation, CylinderPreGraspIsTheFirstSampleInside) {
  const TrialSpec spec;  // pre-grasp at sample 5 (d = 0.4099999 m), grasp at 10, end at 15
  const DemoLog log = MakeTrial(spec);
  const SegmentedTrial s = Segment(log, Cylinder(0.41));
  ASSERT_TRUE(s.ok()) << s.message;
  EXPECT_EQ(s.source, log.source);
  EXPECT_EQ(s.theta_deg, 60.0);
  EXPECT_EQ(s.pregrasp, 5u);
  EXPECT_EQ(s.grasp, 10u);
  EXPECT_EQ(s.end, 15u);
  EXPECT_EQ(s.reach.begin, 0u);
  EXPECT_EQ(s.reach.end, 5u);
  EXPECT_EQ(s.grasping.begin, 5u);
  EXPECT_EQ(s.grasping.end, 11u);
  EXPECT_EQ(s.lifting.begin, 11u);
  EXPECT_EQ(s.lifting.end, 16u);
  EXPECT_EQ(s.reach.size() + s.grasping.size() + s.lifting.size(), log.samples.size());

  const GraspingMotion& m = s.motion;
  std::string why;
  EXPECT_TRUE(IsWellFormed(m, &why)) << why;
  ASSERT_EQ(m.waypoints.size(), 6u);
  EXPECT_NEAR(m.theta, 60.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(m.p_WO, log.samples.front().p_WO);
  EXPECT_THAT(m.source, HasSubstr(log.source));
  EXPECT_EQ(m.waypoints.front().t, 0.0);
  EXPECT_NEAR(m.duration(), 5.0 * spec.dt, 1e-12);
  for (size_t i = 0; i < m.waypoints.size(); ++i) {
    EXPECT_EQ(m.waypoints[i].p_WH, log.samples[5 + i].p_WH);
    EXPECT_EQ(m.waypoints[i].f, log.samples[5 + i].f);
    EXPECT_NEAR(m.waypoints[i].t, log.samples[5 + i].t - log.samples[5].t, 0.0);
  }
  EXPECT_TRUE(
      testing::MatricesNear((m.pregrasp().p_WH - m.p_WO).head<2>(), spec.pregrasp_xy, 1e-12));
  EXPECT_TRUE(testing::MatricesNear((m.grasp().p_WH - m.p_WO).head<2>(), spec.grasp_xy, 1e-12));
}

TEST(Segmentation, InvalidOptionsAreAnInputErrorNotAnAbort) {
  GS_EXPECT_THROW_WITH(Segment(MakeTrial(TrialSpec{}), Cylinder(-1.0)), InputError,
                       "invalid segmentation options: grasp region radius must be finite and > 0");
}

TEST(Segmentation, RegionRadiusAndHeightMoveTheEntry) {
  const DemoLog log = MakeTrial(TrialSpec{});  // approach samples at 0.41 + 0.05 k, k = 5..1
  EXPECT_EQ(Segment(log, Cylinder(0.5)).pregrasp, 4u);   // 0.46 m is the first inside
  EXPECT_EQ(Segment(log, Cylinder(0.55)).pregrasp, 3u);  // 0.51 m, not 0.56 m
  EXPECT_EQ(Segment(log, Cylinder(0.45)).pregrasp, 5u);
  // the wrist stays 0.07 m above the object centre until the lift: outside a 0.1 m cylinder.
  const SegmentedTrial low = Segment(log, Cylinder(0.41, 0.1));
  EXPECT_EQ(low.status, SegmentationStatus::kNeverEntersRegion);
  EXPECT_THAT(low.message, HasSubstr(log.source));
  EXPECT_THAT(low.message, HasSubstr("never enters"));
  EXPECT_EQ(Segment(log, Cylinder(0.41, 0.1401)).pregrasp, 5u);
}

TEST(Segmentation, SphereMeasuresThreeDimensionalDistance) {
  // the pre-grasp sample is 0.4099999 m away horizontally but 0.07 m above the object centre:
  // 0.4159 m in 3D, outside a 0.41 m sphere; the next sample (0.3960 m, 0.4022 m in 3D) is in.
  const DemoLog log = MakeTrial(TrialSpec{});
  const SegmentedTrial cylinder = Segment(log, Cylinder(0.41));
  const SegmentedTrial sphere = Segment(log, Sphere(0.41));
  ASSERT_TRUE(sphere.ok()) << sphere.message;
  EXPECT_EQ(cylinder.pregrasp, 5u);
  EXPECT_EQ(sphere.pregrasp, 6u);
  EXPECT_EQ(sphere.motion.waypoints.size(), 5u);
  EXPECT_EQ(sphere.reach.end, 6u);
  // a sphere large enough to take in the 0.46 m sample in 3D (0.4653 m).
  EXPECT_EQ(Segment(log, Sphere(0.466)).pregrasp, 4u);
  EXPECT_EQ(Segment(log, Sphere(0.465)).pregrasp, 5u);
}

TEST(Segmentation, ReportsTrialsThatEnterOnlyAfterOrAtTheGrasp) {
  TrialSpec spec;
  spec.pregrasp_xy = Polar(0.6, -50.0);
  spec.grasp_xy = Polar(0.5, -60.0);
  DemoLog outside = MakeTrial(spec);
  const SegmentedTrial never = Segment(outside, Cylinder(0.41));
  EXPECT_FALSE(never.ok());
  EXPECT_EQ(never.status, SegmentationStatus::kNeverEntersRegion);
  EXPECT_TRUE(never.motion.waypoints.empty());

  // during the lift the wrist swings over the object: inside only after the grasp.
  DemoLog after = outside;
  for (size_t i = 11; i < after.samples.size(); ++i) {
    after.samples[i].p_WH.head<2>() = after.samples[i].p_WO.head<2>() + Polar(0.2, -60.0);
  }
  const SegmentedTrial late = Segment(after, Cylinder(0.41));
  EXPECT_EQ(late.status, SegmentationStatus::kEntersAfterGrasp);
  EXPECT_THAT(late.message, HasSubstr("at sample 11, after the grasp event at sample 10"));
  EXPECT_TRUE(late.success);  // labelled all the same

  spec.grasp_xy = Polar(0.3, -60.0);
  spec.grasp_samples = 2;
  const SegmentedTrial at = Segment(MakeTrial(spec), Cylinder(0.41));
  EXPECT_EQ(at.status, SegmentationStatus::kEntersAtGrasp);
  EXPECT_THAT(at.message, HasSubstr("single waypoint"));
}

TEST(Segmentation, LabelsSuccessByTheObjectLift) {
  TrialSpec spec;
  spec.lift = 0.10;
  EXPECT_TRUE(Segment(MakeTrial(spec), {}).success);
  spec.lift = 0.05;  // exactly the threshold
  const SegmentedTrial exact = Segment(MakeTrial(spec), {});
  EXPECT_TRUE(exact.success);
  EXPECT_NEAR(exact.lift, 0.05, 1e-15);
  spec.lift = 0.049;
  const SegmentedTrial low = Segment(MakeTrial(spec), {});
  EXPECT_FALSE(low.success);
  EXPECT_TRUE(low.ok());  // an unsuccessful trial is still segmented
  spec.lift = 0.0;
  EXPECT_FALSE(Segment(MakeTrial(spec), {}).success);

  SegmentationOptions strict;
  strict.success_lift = 0.2;
  spec.lift = 0.1;
  EXPECT_FALSE(Segment(MakeTrial(spec), strict).success);
}

TEST(Segmentation, OptionsValidity) {
  std::string why;
  SegmentationOptions o = Cylinder(0.0);
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("radius"));
  o = Cylinder(std::nan(""));
  EXPECT_FALSE(o.IsValid(nullptr));
  o = Cylinder(0.41, -1.0);
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("height"));
  o = Sphere(0.41);
  o.region.height = 0.0;  // a sphere has no height
  EXPECT_TRUE(o.IsValid(nullptr));
  o.success_lift = -0.01;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("success_lift"));
}

TEST(Segmentation, InsideGraspRegionIncludesTheBoundary) {
  GraspRegionModel cylinder;
  cylinder.radius = 0.5;
  cylinder.height = 0.2;
  const Eigen::Vector3d o(1.0, 2.0, 0.0);
  EXPECT_TRUE(InsideGraspRegion(cylinder, o, o + Eigen::Vector3d(0.5, 0.0, 0.1)));
  EXPECT_FALSE(InsideGraspRegion(cylinder, o, o + Eigen::Vector3d(0.5, 0.0, 0.1000001)));
  EXPECT_FALSE(InsideGraspRegion(cylinder, o, o + Eigen::Vector3d(0.3, 0.4000001, 0.0)));
  GraspRegionModel sphere = cylinder;
  sphere.shape = GraspRegionModel::Shape::kSphere;
  EXPECT_TRUE(InsideGraspRegion(sphere, o, o + Eigen::Vector3d(0.0, 0.0, 0.5)));
  EXPECT_FALSE(InsideGraspRegion(sphere, o, o + Eigen::Vector3d(0.3, 0.3, 0.3)));
}

}  // namespace
}  // namespace graspsynth
