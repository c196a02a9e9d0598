// Tests of `graspsynth view` through the built binary (without a browser; the page itself is
// tested by tests/viewer/viewer_screenshot_test.py).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "kinematics/robot_description.hpp"
#include "learning_data/demo_log.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::RunGraspsynth;

class ViewCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("graspsynth_view_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }

  std::filesystem::path dir_;
};

constexpr char kTrajectory[] = R"({"format": "graspsynth-trajectory/1", "theta_deg": 60.0,
  "samples": [
    {"t": 0.0, "arm": [1.96, 0.83, 0, 1.92, -1.76, 1.49, -0.38], "hand": [0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0]},
    {"t": 0.5, "arm": [1.96, 0.83, 0, 1.92, -1.76, 1.49, -0.38], "hand": [1,0,0,0,0,1,0,0,1,0,0,1,0,0,1,0]}]})";

TEST_F(ViewCommand, ReplaysATrajectoryToItsEndAndExits) {
  const std::string file = Write("grasp.json", kTrajectory);
  const auto r = RunGraspsynth("view --trajectory " + file +
                               " --port 0 --no-wait --speed 10 --hold 0.1 --rate 100");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("open http://127.0.0.1:"));
  EXPECT_THAT(r.err, HasSubstr("replay done"));
  EXPECT_EQ(r.out, "");
}

std::string Example() { return std::string(::testing::SourceDir()) + "/examples/grasp_60deg.json"; }

// A grasp file (graspsynth-grasp/1) is taken as the README says: its "trajectory" is simulated
// (the nominal trial) and played as simulated; --joints-only plays the joint commands alone.
TEST_F(ViewCommand, PlaysAGraspFileAsSimulated) {
  const std::string grasp =
      Write("grasp.json", R"({"format": "graspsynth-grasp/1", "trajectory": )" +
                              testing::ReadFileText(Example()) + "}");
  auto r = RunGraspsynth("view --trajectory " + grasp +
                         " --port 0 --no-wait --speed 100 --hold 0 --rate 30");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("nominal trial: success"));
  EXPECT_THAT(r.err, HasSubstr("replay done"));

  r = RunGraspsynth("view --trajectory " + grasp +
                    " --joints-only --port 0 --no-wait --speed 100 --hold 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("nominal trial")));
  EXPECT_THAT(r.err, HasSubstr("replay done"));
}

// A trial record of `simulate --trial-record` plays with --trial, and --trajectory recognises
// one by its format; a broken record, or --at or --joints-only with one, is refused (exit 2).
TEST_F(ViewCommand, PlaysATrialRecord) {
  const std::string record = (dir_ / "trial.json").string();
  ASSERT_EQ(RunGraspsynth("simulate " + Example() + " --trial-record " + record).exit_code, 0);
  for (const char* flag : {"--trial ", "--trajectory "}) {
    const auto r = RunGraspsynth("view " + std::string(flag) + record +
                                 " --port 0 --no-wait --speed 100 --hold 0");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.err, HasSubstr("replay done"));
    EXPECT_THAT(r.err, ::testing::Not(HasSubstr("nominal trial")));  // not simulated again
  }
  auto r = RunGraspsynth("view --trial " + record + " --at -0.3,0.9 --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--at"));
  r = RunGraspsynth("view --trial " + record + " --joints-only --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--joints-only"));
  r = RunGraspsynth("view --joints-only --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--joints-only"));
  r = RunGraspsynth("view --trial " + record + " --trajectory " + record + " --port 0");
  EXPECT_NE(r.exit_code, 0);

  std::string text = testing::ReadFileText(record);
  text.replace(text.find("\"outcome\": \"success\""), 20, "\"outcome\": \"great\"  ");
  const std::string broken = Write("broken.json", text);
  r = RunGraspsynth("view --trial " + broken + " --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("broken.json: field 'outcome'"));
  EXPECT_THAT(r.err, HasSubstr("\"great\""));
  const std::string trajectory = Write("traj.json", kTrajectory);
  r = RunGraspsynth("view --trial " + trajectory + " --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("traj.json: field 'format'"));
}

TEST_F(ViewCommand, ReplaysADemonstrationLog) {
  // a short log: the wrist 8 cm above the handle at theta = 60 deg, still, then the end key.
  const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  Vector7d q;
  q << 1.9572818780320826, 0.8324773213285145, 0.0, 1.9241556706877925, -1.76296224149854,
      1.4935677146794129, -0.3775127214907898;
  const Eigen::Isometry3d X_WH = ArmFlangePose(robot.arm, q) * robot.X_FH;
  DemoLog log;
  log.metadata.theta_deg = 60.0;
  log.metadata.object_position = Eigen::Vector3d(-0.25, 0.85, 0.025);
  for (int k = 0; k < 3; ++k) {
    DemoSample s;
    s.t = 0.1 * k;
    s.p_WH = X_WH.translation();
    s.q_WH = Eigen::Quaterniond(X_WH.linear());
    s.event = k == 1 ? DemoEvent::kGrasp : k == 2 ? DemoEvent::kEnd : DemoEvent::kNone;
    s.p_WO = log.metadata.object_position;
    log.samples.push_back(s);
  }
  log.source = (dir_ / "trial.csv").string();
  WriteDemoLog(log.source, log);
  const auto r = RunGraspsynth("view --log " + log.source + " --port 0 --no-wait --hold 0");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("replay done"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("no IK solution")));
}

TEST_F(ViewCommand, WithNothingToReplayRunsUntilStopped) {
  const auto r = RunGraspsynth("view --port 0 --exit-after 0.3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("waiting for a browser"));
  EXPECT_THAT(r.err, HasSubstr("stopped (--exit-after)"));
}

TEST_F(ViewCommand, RejectsBadOptionsWithTheValue) {
  const std::string file = Write("grasp.json", kTrajectory);
  auto r = RunGraspsynth("view --trajectory " + file + " --port 0 --speed 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--speed: must be > 0 (got 0)"));
  r = RunGraspsynth("view --trajectory " + file + " --port 0 --rate 5000");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--rate: must be"));

  r = RunGraspsynth("view --trajectory " + file + " --port 0 --camera 1,2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("camera placement '1,2'"));

  r = RunGraspsynth("view --trajectory " + file + " --log " + file);
  EXPECT_NE(r.exit_code, 0);

  r = RunGraspsynth("view --port 70000");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("70000"));

  r = RunGraspsynth("view --trajectory " + (dir_ / "missing.json").string());
  EXPECT_NE(r.exit_code, 0);
  EXPECT_THAT(r.err, HasSubstr("missing.json"));

  const std::string bad = Write("bad.json", R"({"format": "graspsynth-trajectory/1"})");
  r = RunGraspsynth("view --port 0 --trajectory " + bad);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json"));
  EXPECT_THAT(r.err, HasSubstr("theta_deg"));

  r = RunGraspsynth("view --address 127.0.0.300 --port 0 --exit-after 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("'127.0.0.300' is not an IPv4 address"));
}

}  // namespace
}  // namespace graspsynth
