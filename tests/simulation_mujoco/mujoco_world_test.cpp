// The exported model in MuJoCo: it loads and steps, and MuJoCo's kinematics of it match ours.

#include "simulation_mujoco/mujoco_world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/errors.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/robot_description.hpp"
#include "scene/scene_model.hpp"
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

// The hand of `graspsynth synthesize --object sugar_box --theta 40 --seed 1` closing on the
// standing sugar box, as in its trajectory from 4.2 s (the hand about to touch the box) to
// 4.69 s: the middle and ring fingertips press on the box's top edge, the thumb on the far face.
// ODE's trial ends this closing with the box tilted 2.1 deg under contact forces of 10-23 N.
// Each finger's servo pushes with at most its cap (0.5 N m, the thumb's 2 N m), so the box is
// pinched, not struck (3.6 deg here); when Drive bounded a finger's gain only at the step's
// start velocity, the step in which a closing finger met the box struck it (contact forces up
// to 160 N), the box rattled between fingers and thumb and ended tilted 15 deg.
TEST_F(MujocoWorld, AClosingHandPinchesTheBoxWithoutStrikingIt) {
  const SimulationModel model(LoadRobotModel(DefaultRobotDescriptionPath()),
                              LoadSceneModel(DefaultSceneModelPath(), "sugar_box"));
  const Placement placement{Radians(40.0), {}};
  const MujocoModel mujoco(model, ExportMjcf(model, placement, {}));
  Vector7d q;
  q << 1.820498, 0.88943, 0.0, 1.557851, 2.837543, 0.899467, 0.192756;
  HandVector open, closed;
  open << 1.555103, 0.002568, 0.394396, 0.058257, -0.333372, 0.553531, 0.145796, 0.001887, 0.560636,
      0.109916, 0.327028, 0.566071, 0.124993, 0.333372, 0.143552, 0.0973;
  closed << 1.53589, 0.005712, 0.55673, 0.129579, -0.314159, 1.231205, 0.32429, 0.004198, 1.247008,
      0.244483, 0.300047, 1.259096, 0.27802, 0.314159, 0.319299, 0.216421;
  MujocoData data(mujoco, q, open);
  int touching_steps = 0;
  for (int n = 1; n <= 800; ++n) {
    const double closing = std::min(1.0, n * 0.001 / 0.49);
    data.SetArmCommand(q);
    data.SetHandCommand(open + closing * (closed - open));
    data.Step();
    ASSERT_TRUE(data.IsFinite());
    if (data.contacts().object_hand > 0) ++touching_steps;
  }
  // the hand did close on the box, and holds it at the end.
  EXPECT_GT(touching_steps, 300);
  EXPECT_GT(data.contacts().object_hand, 0);
  const double tilt = std::acos(std::clamp(data.object_pose().linear()(2, 2), -1.0, 1.0));
  EXPECT_LT(tilt, Radians(5.0)) << "tilt " << tilt / Radians(1.0) << " deg";
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
