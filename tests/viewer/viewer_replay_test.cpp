#include "viewer/viewer_replay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth::viewer {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(testing::ShippedUrdfPath());
  return robot;
}

const SceneModel& Scene() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}

// the arm above the pan's handle at theta = 60 deg (as in viewer_screenshot_test.py).
Vector7d PreGrasp() {
  Vector7d q;
  q << 1.9572818780320826, 0.8324773213285145, 0.0, 1.9241556706877925, -1.76296224149854,
      1.4935677146794129, -0.3775127214907898;
  return q;
}

Eigen::Isometry3d WristPose(const Vector7d& q) {
  return ArmFlangePose(Robot().arm, q) * Robot().X_FH;
}

// A log of 31 samples at 30 Hz: the wrist moves along the FK of a straight joint path, the
// fingers close, the grasp button at sample 20, the object lifts 5 cm over the last 10.
DemoLog SampleLog() {
  DemoLog log;
  log.source = "sample.csv";
  log.metadata.theta_deg = 60.0;
  log.metadata.object_position = Scene().ObjectPose(0.0).translation();
  Vector7d delta;
  delta << 0.2, -0.1, 0.1, 0.15, 0.1, -0.1, 0.2;
  for (int k = 0; k <= 30; ++k) {
    const double s = k / 30.0;
    DemoSample sample;
    sample.t = 2.0 + s;
    const Eigen::Isometry3d X_WH = WristPose(PreGrasp() + s * delta);
    sample.p_WH = X_WH.translation();
    sample.q_WH = Eigen::Quaterniond(X_WH.linear());
    sample.f = HandVector::Constant(0.5 * s);
    sample.event = k == 20 ? DemoEvent::kGrasp : k == 30 ? DemoEvent::kEnd : DemoEvent::kNone;
    sample.p_WO = log.metadata.object_position + Eigen::Vector3d(0, 0, 0.005 * std::max(0, k - 20));
    log.samples.push_back(sample);
  }
  return log;
}

TEST(ViewerReplay, LogWristPosesGoThroughTheIkWithAContinuousArmAngle) {
  const DemoLog log = SampleLog();
  const ViewerReplay replay = ReplayOfLog(Robot(), log);
  ASSERT_EQ(replay.trajectory.samples.size(), log.samples.size());
  EXPECT_EQ(replay.unreached, 0);
  EXPECT_DOUBLE_EQ(replay.start_time(), 2.0);
  EXPECT_DOUBLE_EQ(replay.end_time(), 3.0);
  double largest_step = 0.0;
  for (size_t k = 0; k < log.samples.size(); ++k) {
    const TrajectorySample& s = replay.trajectory.samples[k];
    EXPECT_TRUE(replay.reached[k]);
    EXPECT_TRUE(Robot().arm.WithinLimits(s.arm, 1e-9));
    Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
    X_WH.linear() = log.samples[k].q_WH.toRotationMatrix();
    X_WH.translation() = log.samples[k].p_WH;
    EXPECT_TRUE(testing::PosesNear(WristPose(s.arm), X_WH, 1e-9)) << k;
    EXPECT_TRUE(testing::MatricesNear(s.hand, log.samples[k].f, 0.0));
    if (k > 0) {
      largest_step = std::max(largest_step,
                              (s.arm - replay.trajectory.samples[k - 1].arm).cwiseAbs().maxCoeff());
    }
  }
  // the log's joint path moves each joint by at most 0.2 / 30 rad per sample; the replay's arm
  // angle follows it without jumps.
  EXPECT_LT(largest_step, 0.05);
}

TEST(ViewerReplay, StatesFollowTheLogsObjectAndEvents) {
  const DemoLog log = SampleLog();
  const ViewerReplay replay = ReplayOfLog(Robot(), log);
  const double theta = 60.0 * M_PI / 180.0;

  const ViewerState start = ReplayStateAt(replay, Scene(), 0.0);  // before: the first sample
  EXPECT_DOUBLE_EQ(start.t, 2.0);
  EXPECT_EQ(start.text, "log sample.csv | theta 60.0 deg");
  EXPECT_TRUE(testing::PosesNear(start.X_WO, Scene().ObjectPose(theta), 1e-12));

  // halfway between samples 25 and 26: the object halfway up between their heights.
  const ViewerState lifting = ReplayStateAt(replay, Scene(), 2.0 + 25.5 / 30.0);
  EXPECT_NEAR(lifting.X_WO.translation().z() - log.metadata.object_position.z(), 0.0275, 1e-9);
  EXPECT_TRUE(testing::MatricesNear(Eigen::Matrix3d(lifting.X_WO.linear()),
                                    Eigen::Matrix3d(Scene().ObjectPose(theta).linear()), 1e-12));
  EXPECT_THAT(lifting.text, EndsWith("| grasp"));
  EXPECT_TRUE(testing::MatricesNear(
      lifting.arm, 0.5 * (replay.trajectory.samples[25].arm + replay.trajectory.samples[26].arm),
      1e-12));

  EXPECT_THAT(ReplayStateAt(replay, Scene(), 2.0 + 19.5 / 30.0).text, Not(HasSubstr("grasp")));
  const ViewerState end = ReplayStateAt(replay, Scene(), 10.0);
  EXPECT_DOUBLE_EQ(end.t, 3.0);
  EXPECT_THAT(end.text, EndsWith("| end of trial"));
}

TEST(ViewerReplay, UnreachableWristPosesHoldTheArm) {
  DemoLog log = SampleLog();
  log.samples[0].p_WH.x() += 3.0;   // out of reach before the first reachable pose
  log.samples[10].p_WH.x() += 3.0;  // and in the middle
  const ViewerReplay replay = ReplayOfLog(Robot(), log);
  EXPECT_EQ(replay.unreached, 2);
  EXPECT_FALSE(replay.reached[0]);
  EXPECT_FALSE(replay.reached[10]);
  const auto& samples = replay.trajectory.samples;
  EXPECT_TRUE(testing::MatricesNear(samples[0].arm, samples[1].arm, 0.0));
  EXPECT_TRUE(testing::MatricesNear(samples[10].arm, samples[9].arm, 0.0));
  EXPECT_FALSE(testing::MatricesNear(samples[11].arm, samples[9].arm, 1e-6));
  EXPECT_THAT(ReplayStateAt(replay, Scene(), samples[10].t).text,
              HasSubstr("wrist pose out of reach"));
  EXPECT_THAT(ReplayStateAt(replay, Scene(), samples[11].t).text, Not(HasSubstr("out of reach")));
}

TEST(ViewerReplay, TrajectoryStatesAreItsSamplesWithTheObjectAtRest) {
  JointTrajectory trajectory;
  trajectory.theta_deg = 30.0;
  trajectory.samples.resize(2);
  trajectory.samples[0].arm = PreGrasp();
  trajectory.samples[1].t = 0.5;
  trajectory.samples[1].arm = PreGrasp() + Vector7d::Constant(0.1);
  trajectory.samples[1].hand = HandVector::Constant(0.4);
  const ViewerReplay replay = ReplayOfTrajectory(trajectory, "grasp.json");
  const ViewerState state = ReplayStateAt(replay, Scene(), 0.25);
  EXPECT_TRUE(testing::MatricesNear(state.arm, PreGrasp() + Vector7d::Constant(0.05), 1e-12));
  EXPECT_TRUE(testing::MatricesNear(state.hand, HandVector::Constant(0.2), 1e-12));
  EXPECT_TRUE(testing::PosesNear(state.X_WO, Scene().ObjectPose(30.0 * M_PI / 180.0), 1e-12));
  EXPECT_EQ(state.text, "trajectory grasp.json | theta 30.0 deg");

  // a trajectory made for a moved object shows it there.
  trajectory.object_xy = Eigen::Vector2d(-0.30, 0.90);
  const ViewerReplay moved = ReplayOfTrajectory(trajectory, "grasp.json");
  const ViewerState at = ReplayStateAt(moved, Scene(), 0.25);
  EXPECT_TRUE(testing::PosesNear(
      at.X_WO, Scene().ObjectPose(Placement{30.0 * M_PI / 180.0, trajectory.object_xy}), 1e-12));
  EXPECT_EQ(at.text, "trajectory grasp.json | theta 30.0 deg at (-0.300, 0.900) m");

  const ViewerState rest = ReplayStateAt(RestReplay(), Scene(), 5.0);
  EXPECT_TRUE(rest.arm.isZero());
  EXPECT_DOUBLE_EQ(rest.t, 0.0);
}

// A trial record plays as simulated: the joints of its frames, the object where the physics put
// it (interpolated between frames), the contacts of the frame at or before t, and the outcome
// from the last frame on.
TEST(ViewerReplay, TrialStatesAreTheRecordsFramesAndOutcome) {
  TrialRecord record;
  record.theta_deg = 65.0;
  record.record_interval = 0.5;
  record.outcome = TrialOutcome::kDropped;
  record.reason = "object slipped or dropped: lifted up to 25.9 mm";
  const Eigen::Quaterniond q0 = Eigen::Quaterniond::Identity();
  const Eigen::Quaterniond q1(Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitX()));
  for (int k = 0; k < 2; ++k) {
    TrialRecordFrame f;
    f.t = 0.5 * k;
    f.arm = PreGrasp() + Vector7d::Constant(0.1 * k);
    f.p_WO = Eigen::Vector3d(-0.3, 0.9, 0.025 + 0.1 * k);
    f.q_WO = k == 0 ? q0 : q1;
    if (k == 0) f.contacts.push_back({Eigen::Vector3d(-0.3, 0.85, 0.04), 1.0, 3});
    record.frames.push_back(f);
  }
  const ViewerReplay replay = ReplayOfTrial(record, "trial.json");
  EXPECT_DOUBLE_EQ(replay.end_time(), 0.5);

  const ViewerState mid = ReplayStateAt(replay, Scene(), 0.25);
  EXPECT_TRUE(testing::MatricesNear(mid.arm, PreGrasp() + Vector7d::Constant(0.05), 1e-12));
  EXPECT_TRUE(
      testing::MatricesNear(mid.X_WO.translation(), Eigen::Vector3d(-0.3, 0.9, 0.075), 1e-12));
  EXPECT_NEAR(Eigen::Quaterniond(mid.X_WO.linear()).angularDistance(q0), 0.2, 1e-9);
  ASSERT_EQ(mid.contacts.size(), 1u);
  EXPECT_TRUE(testing::MatricesNear(mid.contacts[0], Eigen::Vector3d(-0.3, 0.85, 0.04), 0.0));
  EXPECT_FALSE(mid.outcome.has_value());  // not decided yet
  EXPECT_EQ(mid.text, "trial trial.json | theta 65.0 deg | as simulated");

  const ViewerState end = ReplayStateAt(replay, Scene(), 3.0);
  EXPECT_TRUE(end.contacts.empty());
  ASSERT_TRUE(end.outcome.has_value());
  EXPECT_FALSE(end.outcome->success);
  EXPECT_EQ(end.outcome->text, "FAILED (dropped): object slipped or dropped: lifted up to 25.9 mm");
  EXPECT_TRUE(testing::PosesNear(end.X_WO, PoseFrom(record.frames[1].p_WO, q1), 1e-12));

  record.outcome = TrialOutcome::kSuccess;
  record.reason = "lifted 120.0 mm";
  const ViewerState won = ReplayStateAt(ReplayOfTrial(record, "t.json"), Scene(), 0.5);
  ASSERT_TRUE(won.outcome.has_value());
  EXPECT_TRUE(won.outcome->success);
  EXPECT_EQ(won.outcome->text, "success: lifted 120.0 mm");
}

}  // namespace
}  // namespace graspsynth::viewer
