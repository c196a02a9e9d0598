// The exported model in MuJoCo: it loads and steps, and MuJoCo's kinematics of it match ours.

#include "simulation_mujoco/mujoco_world.hpp"

#include <gtest/gtest.h>

#include <random>

#include "common/errors.hpp"
#include "kinematics/hand_model.hpp"
#include "simulation/trial_judge.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;
using testing::ShippedSimulationModel;

class MujocoWorld : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  }
};

// a configuration drawn inside the joint limits.
Vector7d RandomArm(const ArmModel& arm, std::mt19937* rng) {
  Vector7d q;
  for (int i = 0; i < kArmDof; ++i) {
    q[i] = std::uniform_real_distribution<double>(arm.lower()[i], arm.upper()[i])(*rng);
  }
  return q;
}

HandVector RandomHand(const HandModel& hand, std::mt19937* rng) {
  HandVector f;
  for (int k = 0; k < kHandDof; ++k) {
    f[k] = std::uniform_real_distribution<double>(hand.lower()[k], hand.upper()[k])(*rng);
  }
  return f;
}

TEST_F(MujocoWorld, FlangeAndHandMatchOurKinematicsTo1e9) {
  const SimulationModel& model = ShippedSimulationModel();
  const RobotModel& robot = model.robot();
  const MujocoModel mujoco(model, ExportMjcf(model, Placement{Radians(60.0), {}}, {}));
  MujocoData data(mujoco, Vector7d::Zero(), HandVector::Zero());
  std::mt19937 rng(7);
  for (int n = 0; n < 25; ++n) {
    const Vector7d q = n == 0 ? Vector7d::Zero() : RandomArm(robot.arm, &rng);
    const HandVector f = RandomHand(robot.hand, &rng);
    data.SetRobotPositions(q, f);
    data.Kinematics();
    ArmFrames frames;
    ArmLinkFrames(robot.arm, q, &frames);
    for (int i = 1; i <= kArmDof; ++i) {
      const Eigen::Isometry3d X = data.arm_link_pose(i);
      EXPECT_LT((X.translation() - frames.X_WL[i].translation()).norm(), 1e-9) << "link " << i;
      EXPECT_LT((X.linear() - frames.X_WL[i].linear()).norm(), 1e-9) << "link " << i;
    }
    // the flange by the DH table, independent of the description's joint origins.
    const Eigen::Isometry3d X_WF = ArmFlangePose(robot.arm, q);
    EXPECT_LT((data.arm_link_pose(kArmDof).translation() - X_WF.translation()).norm(), 1e-9);
    const Eigen::Isometry3d X_WH = X_WF * robot.X_FH;
    EXPECT_LT((data.wrist_pose().translation() - X_WH.translation()).norm(), 1e-9);
    EXPECT_LT((data.wrist_pose().linear() - X_WH.linear()).norm(), 1e-9);
    EXPECT_NEAR((data.arm_positions() - q).norm(), 0.0, 1e-15);
    EXPECT_NEAR((data.hand_positions() - f).norm(), 0.0, 1e-15);
  }
}

TEST_F(MujocoWorld, ObjectRestsOnTheTableAndStaysThere) {
  const SimulationModel& model = ShippedSimulationModel();
  const JointTrajectory& t = ExampleTrajectory();
  const MujocoModel mujoco(model, ExportMjcf(model, t.placement(), {}));
  MujocoData data(mujoco, t.samples.front().arm, t.samples.front().hand);
  const Eigen::Isometry3d X_WO_rest = model.scene().ObjectPose(t.placement());
  EXPECT_LT((data.object_pose().translation() - X_WO_rest.translation()).norm(), 1e-12);
  for (int n = 0; n < 500; ++n) data.Step();
  EXPECT_NEAR(data.time(), 0.5, 1e-9);
  EXPECT_TRUE(data.IsFinite());
  EXPECT_GT(data.contacts().object_table, 0);
  EXPECT_EQ(data.contacts().object_hand, 0);
  // it settles into its contacts by no more than their softness allows, and does not slide.
  const Eigen::Vector3d d = data.object_pose().translation() - X_WO_rest.translation();
  EXPECT_LT(d.head<2>().norm(), 1e-4);
  EXPECT_LT(std::abs(d.z()), 2e-3);
  // the arm holds its configuration against gravity.
  EXPECT_LT((data.arm_positions() - t.samples.front().arm).cwiseAbs().maxCoeff(), 1e-3);
}

TEST_F(MujocoWorld, ServosFollowACommandWithinTheirSpeedLimit) {
  const SimulationModel& model = ShippedSimulationModel();
  const RobotModel& robot = model.robot();
  const MujocoModel mujoco(model, ExportMjcf(model, Placement{}, {}));
  Vector7d q0 = Vector7d::Zero();
  q0[1] = 0.3;
  q0[3] = 1.0;
  MujocoData data(mujoco, q0, HandVector::Zero());
  Vector7d target = q0;
  target[0] += 0.2;  // S1: 1 rad/s at most
  HandVector f = HandVector::Zero();
  f[5] = 0.5;
  data.SetArmCommand(target);
  data.SetHandCommand(f);
  for (int n = 0; n < 100; ++n) data.Step();  // 0.1 s: S1 can move 0.1 rad
  EXPECT_NEAR(data.arm_positions()[0] - q0[0], 0.1, 0.01);
  for (int n = 0; n < 900; ++n) data.Step();
  EXPECT_NEAR(data.arm_positions()[0], target[0], 1e-3);
  EXPECT_NEAR(data.hand_positions()[5], 0.5, 1e-2);
  (void)robot;
}

TEST_F(MujocoWorld, AnArmCommandBeyondItsLimitIsReported) {
  const SimulationModel& model = ShippedSimulationModel();
  const ArmModel& arm = model.robot().arm;
  const MujocoModel mujoco(model, ExportMjcf(model, Placement{}, {}));
  MujocoData data(mujoco, Vector7d::Zero(), HandVector::Zero());
  Vector7d target = Vector7d::Zero();
  target[1] = arm.upper()[1] + 0.1;
  data.SetArmCommand(target);
  data.Step();
  EXPECT_EQ(data.limit_violation(), 1);
  const std::optional<TrialVerdict> v = EarlyVerdict(data, arm, TrialJudgeOptions{});
  ASSERT_TRUE(v.has_value());
  EXPECT_EQ(v->outcome, TrialOutcome::kJointLimit);
}

TEST_F(MujocoWorld, RejectedModelIsAnInputErrorWithMujocosMessage) {
  const SimulationModel& model = ShippedSimulationModel();
  MjcfModel broken = ExportMjcf(model, Placement{}, {});
  broken.xml.replace(broken.xml.find("<worldbody>"), 11, "<worldbodx>");
  try {
    MujocoModel m(model, broken);
    FAIL() << "loaded a broken model";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("MuJoCo rejected the MJCF model"), std::string::npos);
  }
}

}  // namespace
}  // namespace graspsynth
