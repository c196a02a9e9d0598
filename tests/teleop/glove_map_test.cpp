#include "teleop/glove_map.hpp"

#include <gtest/gtest.h>

#include "kinematics/robot_description.hpp"

namespace graspsynth::teleop {
namespace {

const HandModel& Hand() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot.hand;
}

using Glove = Eigen::Matrix<double, 14, 1>;

TEST(GloveMap, OpenGloveOpensTheHandAndClosedGloveClosesIt) {
  const GloveMap map = GloveMap::Default(Hand());
  const HandVector open = GloveToJoints(map, Hand(), Glove::Zero());
  HandVector closed_targets;
  Glove closed = Glove::Ones();
  closed[kIndexMiddle] = closed[kMiddleRing] = closed[kRingLittle] = 0.0;  // fingers together
  const HandVector f = GloveToJoints(map, Hand(), closed);
  // flexion joints: 0 when open, their upper limit when closed.
  for (int k : {2, 3, 5, 6, 8, 9, 11, 12, 14, 15}) {
    EXPECT_DOUBLE_EQ(open[k], std::max(0.0, Hand().lower()[k])) << "f" << k;
    EXPECT_DOUBLE_EQ(f[k], Hand().upper()[k]) << "f" << k;
  }
  EXPECT_TRUE(Hand().WithinLimits(open));
  EXPECT_TRUE(Hand().WithinLimits(f));
}

TEST(GloveMap, FourteenJointsFollowOneSensorEachAndTwoAreDerived) {
  const GloveMap map = GloveMap::Default(Hand());
  int direct = 0;
  std::array<int, 14> used{};
  for (const GloveJointMap& j : map.joints) {
    if (j.sensor >= 0) {
      ++direct;
      ++used[static_cast<size_t>(j.sensor)];
    }
  }
  EXPECT_EQ(direct, 14);
  for (int n : used) EXPECT_EQ(n, 1);
  // each direct joint moves with its sensor alone.
  const HandVector base = GloveToJoints(map, Hand(), Glove::Constant(0.5));
  Glove g = Glove::Constant(0.5);
  g[kIndexFar] = 0.9;
  const HandVector moved = GloveToJoints(map, Hand(), g);
  EXPECT_GT(moved[6], base[6]);
  EXPECT_EQ((moved - base).cwiseAbs().maxCoeff(), std::abs(moved[6] - base[6]));
}

TEST(GloveMap, SpreadMovesTheFingersApartAndOppositionFollowsTheThumb) {
  const GloveMap map = GloveMap::Default(Hand());
  Glove g = Glove::Zero();
  g[kIndexMiddle] = g[kMiddleRing] = g[kRingLittle] = 1.0;
  const HandVector f = GloveToJoints(map, Hand(), g);
  EXPECT_LT(f[4], 0.0);   // index toward the thumb side
  EXPECT_GT(f[10], 0.0);  // ring toward the little side
  EXPECT_GT(f[13], 0.0);
  EXPECT_EQ(f[7], 0.0);  // middle: the reference finger
  Glove thumb_in = Glove::Zero();
  thumb_in[kThumbNear] = 1.0;  // flexed, and no spread from the index
  EXPECT_DOUBLE_EQ(GloveToJoints(map, Hand(), thumb_in)[0], Hand().upper()[0]);
  Glove thumb_out = Glove::Zero();
  thumb_out[kThumbIndex] = 1.0;
  EXPECT_DOUBLE_EQ(GloveToJoints(map, Hand(), thumb_out)[0], Hand().lower()[0]);
}

TEST(GloveMap, OutOfRangeValuesAreClamped) {
  const GloveMap map = GloveMap::Default(Hand());
  const HandVector f = GloveToJoints(map, Hand(), Glove::Constant(7.0));
  EXPECT_TRUE(Hand().WithinLimits(f));
  EXPECT_EQ(f, GloveToJoints(map, Hand(), Glove::Ones()));
}

}  // namespace
}  // namespace graspsynth::teleop
