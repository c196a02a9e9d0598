#include "simulation/simulation_data.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.hpp"
#include "scene/triangle_mesh.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Deg;

const SimulationModel& Model() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

const SimulationModel& ZeroGravityModel() {
  static const SimulationModel model = [] {
    SimulationOptions o;
    o.gravity = 0.0;
    return LoadDefaultSimulationModel(o);
  }();
  return model;
}

// An arm pose with the hand high above the table, away from the object.
Vector7d HighArm() {
  Vector7d q;
  q << Deg(100), Deg(20), Deg(10), Deg(60), Deg(200), Deg(-40), Deg(-190);
  return q;
}

HandVector ClosedHand() {
  HandVector f = HandVector::Zero();
  f.head<4>() << Deg(90), Deg(5), Deg(30), Deg(10);
  for (int finger = 0; finger < 4; ++finger) {
    f[4 + 3 * finger + 1] = Deg(55);
    f[4 + 3 * finger + 2] = Deg(25);
  }
  return f;
}

TEST(WorldOptions, RejectsBadValues) {
  WorldOptions o;
  o.time_step = 0.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("time_step"), std::string::npos);
  GS_EXPECT_THROW_WITH(SimulationData(Model(), o, Vector7d::Zero(), HandVector::Zero()), InputError,
                       "time_step");
}

// ODE's hinge angle has a sign that depends on the order of the attached bodies: the joint
// angles the world measures must be the model's, and the bodies must sit where the
// kinematics put them, including E2 and W2 beyond +-180 deg.
TEST(SimulationData, MeasuredJointsAndBodiesMatchTheKinematics) {
  const RobotModel& robot = ZeroGravityModel().robot();
  WorldOptions options;
  options.arm_mode = ArmMode::kDynamic;
  options.time_step = 0.001;
  const Vector7d q = HighArm();
  const HandVector f = ClosedHand();
  SimulationData data(ZeroGravityModel(), options, q, f);
  for (int i = 0; i < 20; ++i) data.Step();
  EXPECT_TRUE(testing::MatricesNear(data.arm_positions(), q, 1e-6));
  EXPECT_TRUE(testing::MatricesNear(data.hand_positions(), f, 1e-6));
  ArmFrames arm_frames;
  ArmLinkFrames(robot.arm, q, &arm_frames);
  for (int i = 1; i <= kArmDof; ++i) {
    EXPECT_TRUE(testing::PosesNear(data.arm_link_pose(i), arm_frames.X_WL[i], 1e-5)) << i;
  }
  const Eigen::Isometry3d X_WH = arm_frames.X_WL[kArmDof] * robot.X_FH;
  EXPECT_TRUE(testing::PosesNear(data.wrist_pose(), X_WH, 1e-5));
  HandFrames hand_frames;
  HandLinkFrames(robot.hand, f, &hand_frames);
  for (int j = 0; j < robot.hand.joint_count(); ++j) {
    const size_t i = static_cast<size_t>(robot.hand.joint_finger(j));
    const size_t k = static_cast<size_t>(robot.hand.joint_in_finger(j));
    EXPECT_TRUE(testing::PosesNear(data.hand_link_pose(j), X_WH * hand_frames.X_HL[i][k], 1e-5))
        << j;
  }
  // a positive velocity command turns a joint the positive way.
  HandVector v = HandVector::Zero();
  v[5] = 1.0;  // index MCP flexion
  data.SetHandCommand(ServoMode::kVelocity, v);
  for (int i = 0; i < 100; ++i) data.Step();
  EXPECT_NEAR(data.hand_positions()[5], f[5] + 0.1, 2e-3);
}

TEST(SimulationData, ObjectLeftAloneStaysPutForTenSeconds) {
  for (double h : {0.001, 0.004}) {
    WorldOptions options;
    options.time_step = h;
    options.theta = Deg(60);
    SimulationData data(Model(), options, HighArm(), HandVector::Zero());
    const Eigen::Isometry3d X_WO0 = Model().scene().ObjectPose(options.theta);
    EXPECT_TRUE(testing::PosesNear(data.object_pose(), X_WO0, 1e-12));
    double worst = 0.0;
    const int steps = static_cast<int>(std::lround(10.0 / h));
    for (int i = 0; i < steps; ++i) {
      data.Step();
      worst = std::max(worst, (data.object_pose().translation() - X_WO0.translation()).norm());
    }
    EXPECT_LT(worst, 1e-3) << "h = " << h;
    const double tilt =
        Eigen::AngleAxisd(data.object_pose().linear() * X_WO0.linear().transpose()).angle();
    EXPECT_LT(tilt, Deg(0.1)) << "h = " << h;
    EXPECT_GT(data.contacts().object_table, 0);
    EXPECT_EQ(data.contacts().object_hand, 0);
    EXPECT_TRUE(data.IsFinite());
  }
}

// A mesh object (a 10 cm cube as a closed triangle mesh, 0.5 kg) rests on the table as the pan
// does: ODE collides the trimesh with the table box, and it neither sinks nor creeps.
TEST(SimulationData, MeshObjectLeftAloneStaysPut) {
  auto cube = std::make_shared<TriangleMesh>();
  cube->source = "cube";
  for (int i = 0; i < 8; ++i) {
    cube->vertices.emplace_back((i & 1) ? 0.05 : -0.05, (i & 2) ? 0.05 : -0.05,
                                (i & 4) ? 0.05 : -0.05);
  }
  // the six faces, counter-clockwise seen from outside, two triangles each.
  for (const std::array<int, 4>& q : std::vector<std::array<int, 4>>{
           {0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}) {
    cube->triangles.push_back({q[0], q[1], q[2]});
    cube->triangles.push_back({q[0], q[2], q[3]});
  }
  CheckSolidMesh(*cube);
  SceneModel scene = Model().scene();
  ObjectPart part;
  part.name = "cube";
  part.shape.kind = CollisionShape::Kind::kMesh;
  part.shape.mesh = cube;
  part.mass = 0.5;
  scene.object.name = "cube";
  scene.object.parts = {part};
  scene.object.rest_height = 0.05;
  scene.object.handle.reset();
  const SimulationModel model(Model().robot(), scene);
  EXPECT_NEAR(model.object_inertia().I_C(0, 0), 0.5 * 0.02 / 12.0, 1e-12);
  WorldOptions options;
  options.time_step = 0.004;
  SimulationData data(model, options, HighArm(), HandVector::Zero());
  const Eigen::Isometry3d X_WO0 = scene.ObjectPose(0.0);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    data.Step();
    worst = std::max(worst, (data.object_pose().translation() - X_WO0.translation()).norm());
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(data.contacts().object_table, 0);
  EXPECT_TRUE(data.IsFinite());
}

TEST(SimulationData, HandClosingInFreeAirReachesItsTargets) {
  WorldOptions options;
  options.time_step = 0.002;
  SimulationData data(Model(), options, HighArm(), HandVector::Zero());
  const HandVector target = ClosedHand();
  data.SetHandCommand(ServoMode::kPosition, target);
  for (int i = 0; i < 750; ++i) data.Step();
  EXPECT_TRUE(testing::MatricesNear(data.hand_positions(), target, Deg(0.5)));
  // every DIP follows its PIP.
  const HandJointVector q = data.hand_joint_positions();
  const HandModel& hand = Model().robot().hand;
  ASSERT_EQ(q.size(), hand.joint_count());
  for (int finger = 1; finger < hand.finger_count(); ++finger) {
    EXPECT_NEAR(q[hand.JointIndex(finger, 3)], q[hand.JointIndex(finger, 2)], Deg(0.5));
  }
  EXPECT_EQ(data.contacts().object_hand + data.contacts().finger_table, 0);
}

TEST(SimulationData, KinematicStepsFollowTheServosAsTheDynamicsDo) {
  WorldOptions options;
  options.time_step = 0.002;
  SimulationData dynamic(Model(), options, HighArm(), HandVector::Zero());
  SimulationData kinematic(Model(), options, HighArm(), HandVector::Zero());
  Vector7d q_target = HighArm();
  q_target[0] += 0.2;
  q_target[3] -= 0.1;
  for (SimulationData* d : {&dynamic, &kinematic}) {
    d->SetHandCommand(ServoMode::kPosition, ClosedHand());
    d->SetArmCommand(ServoMode::kPosition, q_target);
  }
  for (int i = 0; i < 250; ++i) {
    dynamic.Step();
    kinematic.StepKinematically();
  }
  EXPECT_TRUE(testing::MatricesNear(kinematic.arm_positions(), dynamic.arm_positions(), 1e-12));
  EXPECT_TRUE(testing::MatricesNear(kinematic.hand_positions(), dynamic.hand_positions(), Deg(1)));
  // the object was not stepped at all in the kinematic world.
  EXPECT_TRUE(testing::PosesNear(kinematic.object_pose(), Model().scene().ObjectPose(0.0), 1e-15));
}

TEST(SimulationData, NonFiniteStatesAreErrorsNotCrashes) {
  WorldOptions options;
  SimulationData data(Model(), options, HighArm(), HandVector::Zero());
  data.Step();
  EXPECT_TRUE(data.IsFinite());
  EXPECT_LT(data.MaxDynamicSpeed(), 0.1);
  data.SetObjectVelocity(Eigen::Vector3d(NAN, 0, 0), Eigen::Vector3d::Zero());
  EXPECT_FALSE(data.IsFinite());
  // ODE's own checks would abort the process; they throw instead.
  EXPECT_THROW(
      {
        for (int i = 0; i < 3; ++i) data.Step();
      },
      OdeError);
}

// The Gifu's fingers with index and middle fully actuated and the little finger cut to its
// first joint: 17 joints, 16 actuated (f15 = little_j1); ring_j4 still follows ring_j3.
RobotModel OtherLayout(const std::string& ring_name = "ring") {
  const RobotModel& gifu = Model().robot();
  std::vector<Finger> fingers = gifu.hand.fingers();
  for (size_t i : {1u, 2u}) fingers[i].joints[3].coupling.reset();
  fingers[4].joints.resize(1);
  fingers[4].links.resize(1);
  fingers[3].name = ring_name;
  int actuated = 0;
  for (Finger& finger : fingers) {
    for (HandJoint& hj : finger.joints) {
      if (!hj.coupling) hj.actuated = actuated++;
    }
  }
  return RobotModel{"other.urdf",
                    gifu.arm,
                    gifu.X_FH,
                    HandModel("other.urdf", gifu.hand.mount(), gifu.hand.palm(), gifu.hand.X_HP(),
                              std::move(fingers)),
                    "other",
                    Eigen::Isometry3d::Identity(),
                    {}};
}

TEST(SimulationData, AHandOfAnotherLayoutHasItsBodiesAndHingesAndReachesItsTargets) {
  const SimulationModel model(OtherLayout(), Model().scene());
  const HandModel& hand = model.robot().hand;
  ASSERT_EQ(hand.joint_count(), 17);
  WorldOptions options;
  options.time_step = 0.002;
  SimulationData data(model, options, HighArm(), HandVector::Zero());
  const WorldCounts counts = data.counts();
  EXPECT_EQ(counts.bodies, kArmDof + 17 + 1);
  EXPECT_EQ(counts.joints, 17);                         // the kinematic arm has no hinges
  const HandVector target = HandVector::Constant(0.1);  // inside every joint's range
  data.SetHandCommand(ServoMode::kPosition, target);
  for (int i = 0; i < 500; ++i) data.Step();
  EXPECT_TRUE(testing::MatricesNear(data.hand_positions(), target, Deg(0.5)));
  const HandJointVector q = data.hand_joint_positions();
  ASSERT_EQ(q.size(), 17);
  EXPECT_NEAR(q[hand.JointIndex(3, 3)], q[hand.JointIndex(3, 2)], Deg(0.5));
  EXPECT_NEAR(q[16], 0.1, Deg(0.5));  // the little finger's only joint
  // the little finger's link where the hand's kinematics put it.
  ArmFrames arm_frames;
  ArmLinkFrames(model.robot().arm, data.arm_positions(), &arm_frames);
  HandFrames hand_frames;
  HandLinkFrames(hand, data.hand_positions(), &hand_frames);
  const Eigen::Isometry3d X_WH = arm_frames.X_WL[kArmDof] * model.robot().X_FH;
  EXPECT_TRUE(testing::PosesNear(data.hand_link_pose(16), X_WH * hand_frames.X_HL[4][0], 1e-3));
}

TEST(SimulationModel, RefusesAFingerOutsideTheLoadShareGroups) {
  GS_EXPECT_THROW_WITH(SimulationModel(OtherLayout("annular"), Model().scene()), InputError,
                       "other.urdf", "finger 'annular'", "thumb, index, middle, ring or little");
}

}  // namespace
}  // namespace graspsynth
