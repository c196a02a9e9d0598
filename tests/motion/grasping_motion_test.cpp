#include "motion/grasping_motion.hpp"

#include <gtest/gtest.h>

namespace graspsynth {
namespace {

GraspingMotion TwoWaypoints() {
  GraspingMotion m;
  m.waypoints.resize(2);
  m.waypoints[1].t = 0.5;
  return m;
}

TEST(GraspingMotion, WellFormedMotionPasses) {
  std::string why;
  EXPECT_TRUE(IsWellFormed(TwoWaypoints(), &why)) << why;
  EXPECT_DOUBLE_EQ(TwoWaypoints().duration(), 0.5);
}

TEST(GraspingMotion, EachDefectIsNamed) {
  std::string why;
  GraspingMotion m = TwoWaypoints();
  m.waypoints.pop_back();
  EXPECT_FALSE(IsWellFormed(m, &why));
  EXPECT_EQ(why, "a grasping motion needs at least 2 waypoints");

  m = TwoWaypoints();
  m.waypoints[1].t = 0.0;
  EXPECT_FALSE(IsWellFormed(m, &why));
  EXPECT_EQ(why, "waypoint 1: time does not increase");

  m = TwoWaypoints();
  m.waypoints[1].f[3] = std::nan("");
  EXPECT_FALSE(IsWellFormed(m, &why));
  EXPECT_EQ(why, "waypoint 1: a value is not finite");

  m = TwoWaypoints();
  m.waypoints[0].q_WH.coeffs() *= 1.1;
  EXPECT_FALSE(IsWellFormed(m, &why));
  EXPECT_EQ(why, "waypoint 0: quaternion is not unit");

  m = TwoWaypoints();
  m.waypoints[0].t = 0.1;
  EXPECT_FALSE(IsWellFormed(m, &why));
  EXPECT_EQ(why, "the first waypoint is not at t = 0");
}

}  // namespace
}  // namespace graspsynth
