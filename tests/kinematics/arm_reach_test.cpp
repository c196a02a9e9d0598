// ReachOfTarget (kinematics/arm_reach.hpp): the wrist centre's distance from the shoulder
// against the arm's span, which the analytic IK's reach test uses.

#include "kinematics/arm_reach.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/arm_ik.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

TEST(ArmReach, TheStretchedArmIsAtTheOuterSpanAndTheSpanIsTheArms) {
  const ArmModel arm = testing::Pa10FromDh();
  const SrsLengths& len = arm.lengths();
  const ArmReach reach = ReachOfTarget(arm, ArmFlangePose(arm, Vector7d::Zero()));
  EXPECT_NEAR(reach.distance, len.d_se + len.d_ew, 1e-12);
  EXPECT_DOUBLE_EQ(reach.outer, len.d_se + len.d_ew);
  EXPECT_DOUBLE_EQ(reach.inner, std::abs(len.d_se - len.d_ew));
}

TEST(ArmReach, EveryConfigurationsFlangeIsWithinTheSpan) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937 rng(5);
  for (int k = 0; k < 1000; ++k) {
    Vector7d q;
    for (int i = 0; i < kArmDof; ++i) {
      q[i] = std::uniform_real_distribution<double>(arm.lower()[i], arm.upper()[i])(rng);
    }
    const ArmReach reach = ReachOfTarget(arm, ArmFlangePose(arm, q));
    // the elbow angle alone sets the distance (law of cosines, robot.md 1.5 step 2).
    const double expected = std::sqrt(
        arm.lengths().d_se * arm.lengths().d_se + arm.lengths().d_ew * arm.lengths().d_ew +
        2.0 * arm.lengths().d_se * arm.lengths().d_ew * std::cos(q[3]));
    EXPECT_NEAR(reach.distance, expected, 1e-12) << q.transpose();
    EXPECT_GE(reach.distance, reach.inner - 1e-12);
    EXPECT_LE(reach.distance, reach.outer + 1e-12);
  }
}

TEST(ArmReach, ATargetBeyondTheSpanIsOneTheIkCallsUnreachable) {
  const ArmModel arm = testing::Pa10FromDh();
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
  X_WF.translation() = Eigen::Vector3d(3.0, 0.0, 0.5);
  const ArmReach reach = ReachOfTarget(arm, X_WF);
  EXPECT_GT(reach.distance, reach.outer);
  EXPECT_EQ(PrepareArmTarget(arm, X_WF, 1).status, IkStatus::kUnreachable);
  EXPECT_EQ(PrepareArmTarget(arm, X_WF, -1).status, IkStatus::kUnreachable);
}

}  // namespace
}  // namespace graspsynth
