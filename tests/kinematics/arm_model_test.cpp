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
  GS_EXPECT_THROW_WITH(ArmModel("robot.urdf", good.base(), joints, links), InputError, "robot.urdf",
                       "'S1' and 'S2'", "miss each other");
}

// The joints and links of `good`, for editing.
struct Chain {
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
};
Chain ChainOf(const ArmModel& good) {
  Chain c;
  for (int i = 0; i < kArmDof; ++i) {
    c.joints[i] = good.joint(i);
    c.links[i] = good.link(i + 1);
  }
  return c;
}

TEST(ArmModel, ThePa10sMapIsTheIdentity) {
  const ArmModel arm = testing::Pa10FromDh();
  EXPECT_TRUE(arm.dh_map().identity);
  EXPECT_EQ(arm.dh_lower(), arm.lower());
  EXPECT_EQ(arm.dh_upper(), arm.upper());
  // the identity copies values: a negative zero stays negative.
  Vector7d q = Vector7d::Zero();
  q[3] = -0.0;
  EXPECT_TRUE(std::signbit(arm.dh_map().ToDh(q)[3]));
  EXPECT_TRUE(std::signbit(arm.dh_map().ToJoints(q)[3]));
}

TEST(ArmModel, AFlippedAxisBecomesAJointSign) {
  // E1 turning the other way (the iiwa's A4): the chain is the DH table with E1's sign -1.
  const ArmModel good = testing::Pa10FromDh();
  Chain c = ChainOf(good);
  c.joints[3].axis_J = -c.joints[3].axis_J;
  const ArmModel arm("robot.urdf", good.base(), c.joints, c.links);
  EXPECT_FALSE(arm.dh_map().identity);
  const std::array<int, kArmDof> expected = {1, 1, 1, -1, 1, 1, 1};
  EXPECT_EQ(arm.dh_map().sign, expected);
  EXPECT_EQ(arm.dh_map().offset, Vector7d::Zero());
  EXPECT_EQ(arm.dh_map().R_7F, Eigen::Matrix3d::Identity());
  EXPECT_DOUBLE_EQ(arm.dh_lower()[3], -arm.upper()[3]);
  EXPECT_DOUBLE_EQ(arm.dh_upper()[3], -arm.lower()[3]);
  ArmFrames frames;
  for (int k = 0; k < 50; ++k) {
    const Vector7d q = Vector7d::Random() * 3.0;
    ArmLinkFrames(arm, q, &frames);
    EXPECT_TRUE(PosesNear(frames.X_WL[7], ArmFlangePose(arm, q), 1e-12));
    Vector7d q_dh = q;
    q_dh[3] = -q[3];
    EXPECT_TRUE(PosesNear(ArmFlangePose(arm, q), DhFlangePose(arm.lengths(), q_dh), 1e-15));
  }
}

TEST(ArmModel, ReadsSignsOffsetsAndTheFlangeTurn) {
  // the DH table with offsets on S1 and S2, S2, E1 and W2 flipped, and the flange turned.
  const ArmModel good = testing::Pa10FromDh();
  Chain c = ChainOf(good);
  const Vector7d offset = (Vector7d() << 0.3, -0.2, 0.0, 0.0, 0.0, 0.0, 0.0).finished();
  for (int i = 0; i + 1 < kArmDof; ++i) {
    // joint i at q turns as the DH joint at q + offset_i: the next joint frame turns with it.
    c.joints[i + 1].X_PJ.prerotate(Eigen::AngleAxisd(offset[i], Eigen::Vector3d::UnitZ()));
  }
  for (const int i : {1, 3, 6}) c.joints[i].axis_J = -c.joints[i].axis_J;
  ArmChainOptions options;
  const Eigen::Matrix3d R_7F = (Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  options.X_7F.linear() = R_7F;
  const ArmModel arm("robot.urdf", good.base(), c.joints, c.links, options);
  const std::array<int, kArmDof> expected = {1, -1, 1, -1, 1, 1, -1};
  EXPECT_EQ(arm.dh_map().sign, expected);
  EXPECT_TRUE(testing::MatricesNear(arm.dh_map().offset, offset, 1e-12));
  EXPECT_TRUE(testing::MatricesNear(arm.dh_map().R_7F, R_7F, 1e-12));
  EXPECT_NEAR(arm.lengths().d_wt, 0.070, 1e-12);
  ArmFrames frames;
  for (int k = 0; k < 50; ++k) {
    const Vector7d q = Vector7d::Random() * 3.0;
    ArmLinkFrames(arm, q, &frames);
    EXPECT_TRUE(PosesNear(frames.X_WL[7] * arm.X_7F(), ArmFlangePose(arm, q), 1e-12));
    EXPECT_TRUE(testing::MatricesNear(arm.dh_map().ToJoints(arm.dh_map().ToDh(q)), q, 1e-15));
  }
}

TEST(ArmModel, RejectsAnAxisThatMatchesNoSignOrOffset) {
  const ArmModel good = testing::Pa10FromDh();
  Chain c = ChainOf(good);
  // S2 and everything after it tilted by 0.01 rad about the shoulder: still an SRS chain (the
  // axes meet as before), but S2 is no longer perpendicular to S1, so no offset of S1 turns
  // DH axis 2 onto it.
  c.joints[1].X_PJ.rotate(Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()));
  GS_EXPECT_THROW_WITH(ArmModel("robot.urdf", good.base(), c.joints, c.links), InputError,
                       "robot.urdf", "arm joint 'S2'", "off axis 2", "0.01 rad");
}

TEST(ArmModel, RejectsAnInvalidSrsTolerance) {
  const ArmModel good = testing::Pa10FromDh();
  const Chain c = ChainOf(good);
  ArmChainOptions options;
  options.srs_tolerance_m = 0.0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  GS_EXPECT_THROW_WITH(ArmModel("robot.urdf", good.base(), c.joints, c.links, options), InputError,
                       "robot.urdf", "srs_tolerance_m");
}

}  // namespace
}  // namespace graspsynth
