// Tests of kinematics/robot_grasp.hpp: the robot file's `grasp` part.

#include "kinematics/robot_grasp.hpp"

#include <gtest/gtest.h>

#include <string>

#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/paths.hpp"

namespace graspsynth {
namespace {

const RobotModel& Pa10() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}

// The scripted grasp's hands as the code built them before they were data (Gifu indices:
// thumb f0..f3, index j1 f4, the fingers' j2 at 4 + 3 finger + 1).
HandVector FormerOpenHand() {
  HandVector f = HandVector::Zero();
  f[0] = 90.0 * kDeg;
  f[4] = -20.0 * kDeg;
  f[10] = 20.0 * kDeg;
  f[13] = 20.0 * kDeg;
  f[2] = 15.0 * kDeg;
  return f;
}

HandVector FormerClosedHand() {
  HandVector f = FormerOpenHand();
  f.head<4>() << 90.0 * kDeg, 0.0, 30.0 * kDeg, 10.0 * kDeg;
  for (int finger = 0; finger < 3; ++finger) {
    f[4 + 3 * finger + 1] = 70.0 * kDeg;
    f[4 + 3 * finger + 2] = 17.5 * kDeg;
  }
  f[4 + 3 * 3 + 1] = 20.0 * kDeg;
  f[4 + 3 * 3 + 2] = 10.0 * kDeg;
  return f;
}

TEST(RobotGrasp, ThePa10sFileCarriesTheFormerShapesBitForBit) {
  // a URDF alone (no robot file) takes the shipped robot file of its name.
  ASSERT_FALSE(Pa10().grasp.has_value());
  const RobotGrasp g = RobotGraspOf(Pa10());
  for (int k = 0; k < kHandDof; ++k) {
    EXPECT_EQ(g.open[k], FormerOpenHand()[k]) << "f" << k;
    EXPECT_EQ(g.closed[k], FormerClosedHand()[k]) << "f" << k;
  }
  EXPECT_EQ(g.bar_in_hand, Eigen::Vector3d(0.086, 0.0, 0.103));
}

RobotGrasp Parse(const std::string& grasp_json) {
  const JsonReader top = JsonReader::Parse("{\"grasp\": " + grasp_json + "}", "robot.json");
  return ReadRobotGrasp(top.Field("grasp"), Pa10().hand);
}

TEST(RobotGrasp, ReadsNamedJointsInDegrees) {
  const RobotGrasp g = Parse(
      R"({"bar_in_hand_m": [0.1, 0.01, 0.09], "open_deg": {"index_j2": 10},
          "closed_deg": {"thumb_j3": 30, "little_j3": -0.0}})");
  EXPECT_EQ(g.open[5], 10.0 * kDeg);
  EXPECT_EQ(g.open.cwiseAbs().sum(), 10.0 * kDeg);
  EXPECT_EQ(g.closed[2], 30.0 * kDeg);
  EXPECT_EQ(g.bar_in_hand, Eigen::Vector3d(0.1, 0.01, 0.09));
}

TEST(RobotGrasp, BadPartsAreRefusedNamingTheField) {
  const std::string bar = R"("bar_in_hand_m": [0.1, 0.0, 0.1])";
  GS_EXPECT_THROW_WITH(Parse("{" + bar + R"(, "open_deg": {"index_j4": 10}, "closed_deg": {}})"),
                       InputError, "robot.json", "grasp.open_deg.index_j4",
                       "an actuated joint of the hand (thumb_j1");
  GS_EXPECT_THROW_WITH(Parse("{" + bar + R"(, "open_deg": {}, "closed_deg": {"thumb_j1": 200}})"),
                       InputError, "grasp.closed_deg.thumb_j1", "within thumb_j1's limits");
  GS_EXPECT_THROW_WITH(Parse(R"({"open_deg": {}, "closed_deg": {}})"), InputError,
                       "grasp.bar_in_hand_m");
  GS_EXPECT_THROW_WITH(Parse("{" + bar + R"(, "open_deg": {}, "closed_deg": {}, "x": 1})"),
                       InputError, "x");
}

TEST(RobotGrasp, ARobotWithoutOneIsRefusedNamingIt) {
  RobotModel robot = Pa10();
  robot.name = "no_such_robot";
  GS_EXPECT_THROW_WITH(RobotGraspOf(robot), InputError, "no_such_robot", "has no scripted grasp");
}

}  // namespace
}  // namespace graspsynth
