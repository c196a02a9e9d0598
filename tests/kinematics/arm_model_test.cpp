#include "kinematics/arm_model.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::PosesNear;

TEST(ArmModel, FromDhDerivesItsOwnLengths) {
  const ArmModel arm = testing::Pa10FromDh();
  EXPECT_NEAR(arm.lengths().d_bs, 0.317, 1e-12);
  EXPECT_NEAR(arm.lengths().d_se, 0.450, 1e-12);
  EXPECT_NEAR(arm.lengths().d_ew, 0.480, 1e-12);
  EXPECT_NEAR(arm.lengths().d_wt, 0.070, 1e-12);
}

TEST(ArmModel, ZeroConfigurationPointsStraightUp) {
  const ArmModel arm = testing::Pa10FromDh();
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, Vector7d::Zero());
  EXPECT_TRUE(testing::MatricesNear(X_WF.translation(), Eigen::Vector3d(0, 0, 1.317), 1e-12));
  EXPECT_TRUE(testing::MatricesNear(X_WF.linear(), Eigen::Matrix3d::Identity(), 1e-12));
}

TEST(ArmModel, ElbowBentNinetyDegreesPutsTheForearmHorizontal) {
  // E1 = 90 deg turns the forearm about the elbow axis (world y at q = 0, DH frame 3's z).
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q = Vector7d::Zero();
  q[3] = M_PI / 2;
  const Eigen::Vector3d p = ArmFlangePose(arm, q).translation();
  EXPECT_NEAR(p.z(), 0.317 + 0.450, 1e-12);
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.480 + 0.070, 1e-12);
}

TEST(ArmModel, LinkFramesEndAtTheDhFlange) {
  const ArmModel arm = testing::Pa10FromDh();
  ArmFrames frames;
  for (int k = 0; k < 50; ++k) {
    const Vector7d q = Vector7d::Random() * 3.0;
    ArmLinkFrames(arm, q, &frames);
    EXPECT_TRUE(PosesNear(frames.X_WL[7], ArmFlangePose(arm, q), 1e-12));
  }
}

TEST(ArmModel, RejectsAnEmptyJointRange) {
  Vector7d lower = testing::Pa10Lower();
  lower[2] = 4.0;
  GS_EXPECT_THROW_WITH(ArmModel::FromDh({0.317, 0.45, 0.48, 0.07}, lower, testing::Pa10Upper(),
                                        Vector7d::Ones(), Vector7d::Ones()),
                       InputError, "arm joint 'S3'", "empty position range");
}

TEST(ArmModel, RejectsAJointOffTheShoulder) {
  const ArmModel good = testing::Pa10FromDh();
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
  for (int i = 0; i < kArmDof; ++i) {
    joints[i] = good.joint(i);
    links[i] = good.link(i + 1);
  }
  joints[1].X_PJ.translation().x() += 0.01;  // S2 no longer meets S1
  GS_EXPECT_THROW_WITH(ArmModel("robot.urdf", good.base(), joints, links), InputError,
                       "robot.urdf", "'S1' and 'S2'", "miss each other");
}

TEST(ArmModel, RejectsAFlippedAxisThatBreaksTheDhTable) {
  const ArmModel good = testing::Pa10FromDh();
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
  for (int i = 0; i < kArmDof; ++i) {
    joints[i] = good.joint(i);
    links[i] = good.link(i + 1);
  }
  joints[3].axis_J = -joints[3].axis_J;  // E1 turning the other way
  GS_EXPECT_THROW_WITH(ArmModel("robot.urdf", good.base(), joints, links), InputError,
                       "does not follow the standard DH table");
}

}  // namespace
}  // namespace graspsynth
