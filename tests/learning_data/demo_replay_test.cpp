// Tests of ReplayDemoLog: a log's wrist poses and fingers become a joint trajectory that plays
// them back, or a clear failure naming the sample that cannot be played.

#include "learning_data/demo_replay.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "simulation/simulation_model.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/scripted_demos.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;

TEST(ReplayDemoLog, PlaysTheLoggedWristPosesAndFingers) {
  const SimulationModel model = LoadDefaultSimulationModel();
  const DemoLog log = testing::ScriptedDemoLog(model, 60.0, "scripted60.csv");
  ASSERT_FALSE(log.samples.empty());
  const DemoReplay replay = ReplayDemoLog(model.robot(), log);
  ASSERT_TRUE(replay.ok) << replay.message;
  const JointTrajectory& trajectory = replay.trajectory;
  ASSERT_EQ(trajectory.samples.size(), log.samples.size());
  EXPECT_EQ(trajectory.theta_deg, 60.0);
  for (size_t i = 0; i < log.samples.size(); i += 7) {
    const Eigen::Isometry3d X_WH =
        ArmFlangePose(model.robot().arm, trajectory.samples[i].arm) * model.robot().X_FH;
    EXPECT_TRUE(testing::MatricesNear(X_WH.translation(), log.samples[i].p_WH, 1e-9))
        << "sample " << i;
    EXPECT_LT(Eigen::AngleAxisd(X_WH.linear().transpose() *
                                log.samples[i].q_WH.normalized().toRotationMatrix())
                  .angle(),
              1e-9);
    EXPECT_TRUE(testing::MatricesNear(trajectory.samples[i].hand, log.samples[i].f, 0.0));
  }
  // waypoints: first sample, grasp event, last sample.
  ASSERT_EQ(trajectory.waypoints.size(), 3u);
  EXPECT_EQ(trajectory.waypoints.front().t, trajectory.samples.front().t);
  EXPECT_EQ(trajectory.waypoints.back().t, trajectory.samples.back().t);
  // the replay succeeds in the simulation as the log says the trial did.
  const TrialResult result = RunTrial(model, trajectory);
  EXPECT_TRUE(result.success()) << result.BriefReport();
}

TEST(ReplayDemoLog, AnUnreachableSampleIsAFailureNamingIt) {
  const SimulationModel model = LoadDefaultSimulationModel();
  DemoLog log = testing::ScriptedDemoLog(model, 60.0, "far.csv");
  ASSERT_GT(log.samples.size(), 30u);
  log.samples[30].p_WH.x() += 3.0;  // 3 m away: out of the arm's reach
  const DemoReplay replay = ReplayDemoLog(model.robot(), log);
  EXPECT_FALSE(replay.ok);
  EXPECT_THAT(replay.message, HasSubstr("far.csv: sample 31"));
}

TEST(ReplayDemoLog, AnUnreachableStartIsAFailure) {
  const SimulationModel model = LoadDefaultSimulationModel();
  DemoLog log = testing::ScriptedDemoLog(model, 60.0, "start.csv");
  ASSERT_FALSE(log.samples.empty());
  log.samples.front().p_WH.z() += 5.0;
  const DemoReplay replay = ReplayDemoLog(model.robot(), log);
  EXPECT_FALSE(replay.ok);
  EXPECT_THAT(replay.message, HasSubstr("start.csv"));
}

}  // namespace
}  // namespace graspsynth
