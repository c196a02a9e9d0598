#include "simulation/trial_judge.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "motion/scripted_grasp.hpp"
#include "scene/rest_pose.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::ShippedSimulationModel;

constexpr double kTheta = 60.0;

WorldOptions Options() {
  WorldOptions options;
  options.time_step = 0.004;
  options.arm_mode = ArmMode::kKinematic;
  options.theta = kTheta * M_PI / 180.0;
  return options;
}

// The shipped world at 60 deg, the arm at its rest pose (far from the object), the hand open.
SimulationData RestWorld() {
  const SimulationModel& model = ShippedSimulationModel();
  ScriptedGraspOptions grasp;
  grasp.theta_deg = kTheta;
  const Vector7d rest = DefaultRestConfiguration(
      model.robot(), model.scene(), GraspWristPose(model.robot(), model.scene(), grasp).linear());
  return SimulationData(model, Options(), rest, RobotGraspOf(model.robot()).open);
}

// The same world with the hand pushed into the table beside the object (the last sample of
// testing::HandThroughTable).
SimulationData FingersInTheTable() {
  const JointTrajectory through_table = testing::HandThroughTable();
  const TrajectorySample& at = through_table.samples.back();
  return SimulationData(ShippedSimulationModel(), Options(), at.arm, at.hand);
}

Eigen::Isometry3d RestObjectPose() {
  return ShippedSimulationModel().scene().ObjectPose(kTheta * M_PI / 180.0);
}

TEST(TrialOutcome, NamesAreTheReportNames) {
  EXPECT_EQ(ToString(TrialOutcome::kSuccess), "success");
  EXPECT_EQ(ToString(TrialOutcome::kNotLifted), "not_lifted");
  EXPECT_EQ(ToString(TrialOutcome::kDropped), "dropped");
  EXPECT_EQ(ToString(TrialOutcome::kKnockedOver), "knocked_over");
  EXPECT_EQ(ToString(TrialOutcome::kTouchesOther), "touches_other");
  EXPECT_EQ(ToString(TrialOutcome::kTilted), "tilted");
  EXPECT_EQ(ToString(TrialOutcome::kCollision), "collision");
  EXPECT_EQ(ToString(TrialOutcome::kJointLimit), "joint_limit");
  EXPECT_EQ(ToString(TrialOutcome::kUnstable), "unstable");
}

TEST(TrialJudgeOptions, DefaultsAreValidAndBadValuesAreNamed) {
  std::string why;
  EXPECT_TRUE(TrialJudgeOptions{}.IsValid(&why)) << why;
  TrialJudgeOptions o;
  o.lifted_min = 0.06;  // above lift_threshold
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("lifted_min"));
  o = {};
  o.max_kinetic_energy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("max_kinetic_energy"));
}

TEST(StepTrialWorld, FreeSpaceIsKinematicUntilSomethingTouches) {
  SimulationData far = RestWorld();
  bool free_space = true;
  for (int k = 0; k < 10; ++k) StepTrialWorld(&far, &free_space);
  EXPECT_TRUE(free_space);
  EXPECT_EQ(far.statistics().kinematic_steps, 10);
  EXPECT_EQ(far.statistics().dynamic_steps, 0);

  // a touch ends free space: the step that finds it is kinematic, the next ones are full.
  SimulationData touching = FingersInTheTable();
  free_space = true;
  StepTrialWorld(&touching, &free_space);
  EXPECT_FALSE(free_space);
  const ContactReport& c = touching.contacts();
  EXPECT_GT(c.object_hand + c.object_arm + c.finger_table, 0);
  StepTrialWorld(&touching, &free_space);
  EXPECT_EQ(touching.statistics().kinematic_steps, 1);
  EXPECT_EQ(touching.statistics().dynamic_steps, 1);
}

TEST(EarlyVerdict, NothingAtRestAndInstabilityWhenTheObjectRunsAway) {
  SimulationData data = RestWorld();
  bool free_space = true;
  StepTrialWorld(&data, &free_space);
  const ArmModel& arm = ShippedSimulationModel().robot().arm;
  EXPECT_FALSE(EarlyVerdict(data, arm, TrialJudgeOptions{}).has_value());

  data.SetObjectVelocity(Eigen::Vector3d(0.0, 0.0, 8.0), Eigen::Vector3d::Zero());
  const std::optional<TrialVerdict> fast = EarlyVerdict(data, arm, TrialJudgeOptions{});
  ASSERT_TRUE(fast.has_value());
  EXPECT_EQ(fast->outcome, TrialOutcome::kUnstable);
  EXPECT_THAT(fast->reason, HasSubstr("numerical instability at t = 0.004 s: speed 8 m/s"));

  // the same speed under a higher limit (and an energy limit above its energy) is no verdict.
  TrialJudgeOptions lenient;
  lenient.max_speed = 10.0;
  lenient.max_kinetic_energy = 100.0;
  EXPECT_FALSE(EarlyVerdict(data, arm, lenient).has_value());
}

TEST(OdeFailureVerdict, IsUnstableWithTheTimeAndWhatOdeSaid) {
  const TrialVerdict v = OdeFailureVerdict(1.25, "dxJointGroup overflow");
  EXPECT_EQ(v.outcome, TrialOutcome::kUnstable);
  EXPECT_EQ(v.reason, "numerical instability at t = 1.250 s: dxJointGroup overflow");
}

TEST(JudgeTrial, AnUntouchedObjectIsNotLifted) {
  SimulationData data = RestWorld();
  TrialWatch watch = StartTrialWatch(RestObjectPose());
  bool free_space = true;
  for (int k = 0; k < 20; ++k) {
    StepTrialWorld(&data, &free_space);
    WatchStep(data, TrialJudgeOptions{}, &watch);
  }
  EXPECT_NEAR(watch.max_lift, 0.0, 1e-6);
  EXPECT_NEAR(watch.max_shift, 0.0, 1e-6);
  EXPECT_FALSE(watch.was_lifted);
  const TrialVerdict v = JudgeTrial(data, watch, 1.0, TrialJudgeOptions{});
  EXPECT_EQ(v.outcome, TrialOutcome::kNotLifted);
  EXPECT_EQ(v.reason, "object not lifted: its centre rose at most 0.0 mm (needs 50 mm)");
}

// The watch judges against the rest pose it was started with: a rest pose lower, or beside
// the object's, reads as a lift, or a shift, of the object lying on the table.
TEST(JudgeTrial, TheWatchDecidesDroppedAndKnockedOver) {
  SimulationData data = RestWorld();
  // dynamic steps: the object's table contacts are detected.
  bool free_space = false;
  for (int k = 0; k < 5; ++k) StepTrialWorld(&data, &free_space);
  ASSERT_GT(data.contacts().object_table, 0);

  Eigen::Isometry3d below = RestObjectPose();
  below.translation().z() -= 0.08;
  TrialWatch lifted = StartTrialWatch(below);
  WatchStep(data, TrialJudgeOptions{}, &lifted);
  EXPECT_NEAR(lifted.max_lift, 0.08, 1e-3);
  EXPECT_LT(lifted.airborne_since, 0.0);  // on the table: not airborne
  const TrialVerdict dropped = JudgeTrial(data, lifted, 1.0, TrialJudgeOptions{});
  EXPECT_EQ(dropped.outcome, TrialOutcome::kDropped);
  EXPECT_THAT(dropped.reason, HasSubstr("object slipped or dropped: lifted up to 80.0 mm"));
  EXPECT_THAT(dropped.reason, HasSubstr(", back on the table"));

  Eigen::Isometry3d beside = RestObjectPose();
  beside.translation().x() += 0.05;
  TrialWatch pushed = StartTrialWatch(beside);
  WatchStep(data, TrialJudgeOptions{}, &pushed);
  EXPECT_NEAR(pushed.max_shift, 0.05, 1e-3);
  const TrialVerdict knocked = JudgeTrial(data, pushed, 1.0, TrialJudgeOptions{});
  EXPECT_EQ(knocked.outcome, TrialOutcome::kKnockedOver);
  EXPECT_THAT(knocked.reason, HasSubstr("moved 50.0 mm on the table"));
  // a larger shift threshold: not knocked over, not lifted.
  TrialJudgeOptions tolerant;
  tolerant.knocked_shift = 0.1;
  EXPECT_EQ(JudgeTrial(data, pushed, 1.0, tolerant).outcome, TrialOutcome::kNotLifted);
}

}  // namespace
}  // namespace graspsynth
