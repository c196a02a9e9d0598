#include "motion/scripted_grasp.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/robot_file.hpp"
#include "scene/base_frame.hpp"
#include "simulation/trial.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ShippedSimulationModel;

const RobotModel& Robot() { return ShippedSimulationModel().robot(); }
const SceneModel& Scene() { return ShippedSimulationModel().scene(); }

// examples/grasp_60deg.json is `graspsynth scripted-grasp --theta 60`: regenerate it with that
// command when the builder changes.
TEST(ScriptedGrasp, TheShippedExampleIsTheGeneratorsOutput) {
  const ScriptedGraspResult r = BuildScriptedGrasp(Robot(), Scene(), ScriptedGraspOptions{});
  ASSERT_TRUE(r.ok) << r.message;
  const JointTrajectory& shipped = testing::ExampleTrajectory();
  EXPECT_EQ(shipped.theta_deg, 60.0);
  ASSERT_EQ(shipped.samples.size(), r.trajectory.samples.size());
  for (size_t i = 0; i < shipped.samples.size(); ++i) {
    // the file rounds to 1e-10.
    EXPECT_NEAR(shipped.samples[i].t, r.trajectory.samples[i].t, 1e-9) << i;
    EXPECT_TRUE(testing::MatricesNear(shipped.samples[i].arm, r.trajectory.samples[i].arm, 1e-9))
        << i;
    EXPECT_TRUE(testing::MatricesNear(shipped.samples[i].hand, r.trajectory.samples[i].hand, 1e-9))
        << i;
  }
  ASSERT_EQ(shipped.waypoints.size(), r.trajectory.waypoints.size());
  for (size_t i = 0; i < shipped.waypoints.size(); ++i) {
    EXPECT_TRUE(
        testing::PosesNear(shipped.waypoints[i].pose(), r.trajectory.waypoints[i].pose(), 1e-9));
  }
}

TEST(ScriptedGrasp, TheWristPutsTheHandleWhereTheHandPinches) {
  for (double theta : {40.0, 60.0, 80.0}) {
    ScriptedGraspOptions o;
    o.theta_deg = theta;
    const Eigen::Isometry3d X_WH = GraspWristPose(Robot(), Scene(), o);
    const Eigen::Isometry3d X_WO = Scene().ObjectPose(theta * M_PI / 180.0);
    // the bar point of the hand lies on the handle's axis, grasp_radius from the centre.
    const Eigen::Vector3d p_O = X_WO.inverse() * (X_WH * RobotGraspOf(Robot()).bar_in_hand);
    EXPECT_NEAR(p_O.x(), o.grasp_radius, 1e-12);
    EXPECT_NEAR(p_O.y(), 0.0, 1e-12);
    EXPECT_NEAR(p_O.z(), Scene().object.handle->axis_height - Scene().object.rest_height, 1e-12);
    // palm down, the hand across the handle, the thumb side toward the pan.
    EXPECT_TRUE(testing::MatricesNear(X_WH.linear().col(0), -Eigen::Vector3d::UnitZ(), 1e-12));
    EXPECT_NEAR(X_WH.linear().col(2).dot(X_WO.linear().col(0)), 0.0, 1e-12);
    EXPECT_NEAR(X_WH.linear().col(1).dot(X_WO.linear().col(0)), -1.0, 1e-12);
  }
}

TEST(ScriptedGrasp, TheTrajectoryIsPlayableAndPassesThroughItsWaypoints) {
  const ScriptedGraspOptions o;
  const ScriptedGraspResult r = BuildScriptedGrasp(Robot(), Scene(), o);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_NO_THROW(CheckJointLimits(r.trajectory, Robot().arm, Robot().hand, "scripted"));
  ASSERT_EQ(r.trajectory.waypoints.size(), 5u);
  for (const WristWaypoint& w : r.trajectory.waypoints) {
    const TrajectorySample s = SampleAt(r.trajectory, w.t);
    EXPECT_TRUE(
        testing::PosesNear(ArmFlangePose(Robot().arm, s.arm) * Robot().X_FH, w.pose(), 1e-9))
        << "t = " << w.t;
  }
  EXPECT_TRUE(testing::PosesNear(r.trajectory.waypoints[2].pose(), r.X_WH_grasp, 1e-9));
  EXPECT_TRUE(testing::PosesNear(r.trajectory.waypoints[1].pose(), r.X_WH_pregrasp, 1e-9));
  const double total = o.reach_duration + o.approach_duration + o.close_duration +
                       o.settle_duration + o.lift_duration + o.end_duration;
  EXPECT_NEAR(r.trajectory.duration(), total, 1e-9);  // slow enough: no re-timing
  // the hand opens before and closes after the approach.
  EXPECT_EQ(SampleAt(r.trajectory, r.trajectory.waypoints[2].t).hand, RobotGraspOf(Robot()).open);
  EXPECT_EQ(r.trajectory.samples.back().hand, RobotGraspOf(Robot()).closed);
  // no joint jumps: consecutive samples within 0.05 rad.
  for (size_t i = 1; i < r.trajectory.samples.size(); ++i) {
    EXPECT_LT((r.trajectory.samples[i].arm - r.trajectory.samples[i - 1].arm).cwiseAbs().maxCoeff(),
              0.05);
  }
}

TEST(ScriptedGrasp, RejectsInvalidOptions) {
  ScriptedGraspOptions o;
  o.side = 0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  GS_EXPECT_THROW_WITH(BuildScriptedGrasp(Robot(), Scene(), o), InputError, "side");
  o = {};
  o.close_duration = 0.0;
  GS_EXPECT_THROW_WITH(BuildScriptedGrasp(Robot(), Scene(), o), InputError, "duration");
}

TEST(ScriptedGrasp, AnUnreachableGraspIsAResult) {
  ScriptedGraspOptions o;
  o.grasp_radius = 3.0;  // far beyond the arm's reach
  const ScriptedGraspResult r = BuildScriptedGrasp(Robot(), Scene(), o);
  EXPECT_FALSE(r.ok);
  EXPECT_FALSE(r.message.empty());
}

// The KUKA LBR iiwa 14 with the Allegro hand, standing at its robot file's base, grasps and lifts
// the pan with its robot file's grasp part (the hand shapes found by search in ODE): the pan
// ends 5 cm or more up, held by the hand alone, and the contact normals are horizontal, so that
// friction carries the weight (as the Gifu's pinch does).
TEST(ScriptedGrasp, TheIiwaWithTheAllegroHandLiftsThePanByFriction) {
  const SimulationModel model(LoadRobotOption("iiwa14_allegro"),
                              LoadSceneModel(DefaultSceneModelPath()));
  ASSERT_TRUE(model.robot().grasp.has_value());
  EXPECT_NE(model.robot().X_WB.matrix(), Eigen::Isometry3d::Identity().matrix());
  for (double theta : {40.0, 60.0, 80.0}) {
    ScriptedGraspOptions o;
    o.theta_deg = theta;
    const ScriptedGraspResult g = BuildScriptedGrasp(model.robot(), model.scene(), o);
    ASSERT_TRUE(g.ok) << theta << ": " << g.message;
    // the arm plays it within its limits, the hand at the robot file's shapes.
    EXPECT_NO_THROW(CheckJointLimits(g.trajectory, model.robot().arm, model.robot().hand, "iiwa"));
    EXPECT_EQ(g.trajectory.samples.back().hand, model.robot().grasp->closed);
    const TrialResult r = RunTrial(model, g.trajectory, TrialOptions{});
    EXPECT_TRUE(r.success()) << theta << ": " << r.BriefReport();
    EXPECT_GT(r.lift, 0.05) << theta;
    EXPECT_LT(r.hold.slip, 0.01) << theta;
    // friction holds it: the contacts' normal forces carry under 10% of the weight.
    double normal_up = 0.0, up = 0.0;
    for (const HandObjectContact& c : r.end_contacts) {
      normal_up += c.f_W.dot(c.n_W) * c.n_W.z();
      up += c.f_W.z();
    }
    ASSERT_GT(up, 0.0) << theta;
    EXPECT_LT(std::abs(normal_up) / up, 0.1) << theta;
  }
}

}  // namespace
}  // namespace graspsynth
