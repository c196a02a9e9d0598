#include "motion/resample.hpp"

#include <gtest/gtest.h>

#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/motion_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::LineMotion;
using testing::MatricesNear;

TEST(SampleAt, ReproducesWaypointsAndInterpolatesBetween) {
  const GraspingMotion m =
      LineMotion({0, 0, 0}, {0.3, 0, 0}, 0.6, 1.0, 7, 1.2, Eigen::Vector3d(1, 2, 3));
  for (const MotionWaypoint& w : m.waypoints) {
    const MotionWaypoint s = SampleAt(m, w.t);
    EXPECT_TRUE(MatricesNear(s.p_WH, w.p_WH, 1e-15));
    EXPECT_LT(AngleBetween(s.q_WH, w.q_WH), 1e-12);
    EXPECT_TRUE(MatricesNear(s.f, w.f, 1e-15));
  }
  const MotionWaypoint mid = SampleAt(m, 0.5 * (m.waypoints[2].t + m.waypoints[3].t));
  EXPECT_TRUE(MatricesNear(mid.p_WH, 0.5 * (m.waypoints[2].p_WH + m.waypoints[3].p_WH), 1e-15));
  // clamped outside the motion.
  EXPECT_TRUE(MatricesNear(SampleAt(m, -1.0).p_WH, m.pregrasp().p_WH, 0.0));
  EXPECT_TRUE(MatricesNear(SampleAt(m, 9.0).p_WH, m.grasp().p_WH, 0.0));
}

TEST(Resample, KeepsEndpointsExactlyAndSpacesTimeEvenly) {
  const GraspingMotion m = LineMotion({0, 0, 0}, {0.3, 0.1, 0}, 0.6, 1.0, 13, 1.2);
  const GraspingMotion r = Resample(m, 25);
  ASSERT_EQ(r.waypoints.size(), 25u);
  std::string why;
  EXPECT_TRUE(IsWellFormed(r, &why)) << why;
  EXPECT_TRUE(MatricesNear(r.pregrasp().p_WH, m.pregrasp().p_WH, 0.0));
  EXPECT_TRUE(MatricesNear(r.grasp().p_WH, m.grasp().p_WH, 0.0));
  EXPECT_EQ(r.grasp().t, m.grasp().t);
  for (size_t k = 0; k < r.waypoints.size(); ++k) {
    EXPECT_NEAR(r.waypoints[k].t, 1.2 * static_cast<double>(k) / 24.0, 1e-12);
  }
}

TEST(Resample, ArcLengthSpacesThePathEvenly) {
  // the cosine profile is slow at both ends: time spacing crowds the path there, arc length
  // spacing does not.
  const GraspingMotion m = LineMotion({0, 0, 0}, {0.4, 0, 0}, 0.0, 1.0, 201, 2.0);
  const GraspingMotion r = Resample(m, 11, ResampleMode::kArcLength);
  for (size_t k = 1; k < r.waypoints.size(); ++k) {
    EXPECT_NEAR((r.waypoints[k].p_WH - r.waypoints[k - 1].p_WH).norm(), 0.04, 1e-12);
    EXPECT_GT(r.waypoints[k].t, r.waypoints[k - 1].t);
  }
  const GraspingMotion by_time = Resample(m, 11);
  EXPECT_LT((by_time.waypoints[1].p_WH - by_time.waypoints[0].p_WH).norm(), 0.01);
}

TEST(Resample, StillWristFallsBackToTime) {
  const GraspingMotion m = LineMotion({0.1, 0, 0}, {0.1, 0, 0}, 0.3, 1.0, 5, 1.0);
  const GraspingMotion r = Resample(m, 3, ResampleMode::kArcLength);
  EXPECT_NEAR(r.waypoints[1].t, 0.5, 1e-12);
}

}  // namespace
}  // namespace graspsynth
