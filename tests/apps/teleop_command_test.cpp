// graspsynth teleop and teleop-client: the whole loop over loopback UDP. A synthetic trial (the
// scripted grasp at theta = 60 deg as a 60 Hz log) is replayed by the client into a recording
// server; the recorded trial must have the same outcome and a grasp pose within tolerance.

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "learning_data/demo_log.hpp"
#include "learning_data/segmentation.hpp"
#include "tests/teleop/teleop_fixtures.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

extern char** environ;

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using testing::RunGraspsynth;

fs::path TempDir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("graspsynth_teleop_cmd_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// `graspsynth args...` in the background.
pid_t Spawn(const std::vector<std::string>& args) {
  std::vector<std::string> all = {::testing::GraspsynthBinary()};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = -1;
  EXPECT_EQ(
      posix_spawn(&pid, ::testing::GraspsynthBinary(), nullptr, nullptr, argv.data(), environ), 0);
  return pid;
}

// the exit status of `pid`, waiting at most `seconds` (then it is killed: -1).
int WaitFor(pid_t pid, double seconds) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < until) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -1;
}

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.normalized().angularDistance(b.normalized());
}

TEST(TeleopCommand, HelpExplainsTheLoopAndTheClient) {
  const testing::CommandOutput server = RunGraspsynth("teleop --help");
  EXPECT_EQ(server.exit_code, 0);
  for (const char* word :
       {"--port", "--bind", "--orientations", "--record", "--rate", "--calibration", "--config",
        "--timeout-ms", "--viewer-port", "--summary", "graspsynth-teleop-session/1"}) {
    EXPECT_NE(server.out.find(word), std::string::npos) << word;
  }
  const testing::CommandOutput client = RunGraspsynth("teleop-client --help");
  EXPECT_EQ(client.exit_code, 0);
  for (const char* word : {"--replay", "--port", "--host", "--speed", "--calibration"}) {
    EXPECT_NE(client.out.find(word), std::string::npos) << word;
  }
}

TEST(TeleopCommand, BadOptionsAreNamed) {
  const testing::CommandOutput r = RunGraspsynth("teleop --orientations 20,abc --port 0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--orientations: 'abc' is not a finite number of degrees (in '20,abc')"),
            std::string::npos)
      << r.err;
  const testing::CommandOutput t = RunGraspsynth("teleop --timeout-ms -5 --port 0");
  EXPECT_EQ(t.exit_code, 2);
  EXPECT_NE(t.err.find("--timeout-ms"), std::string::npos) << t.err;
}

// The link beyond this machine needs a key (or --insecure); keygen writes one that the server
// and the client share.
TEST(TeleopCommand, BindingBeyondLoopbackNeedsAKeyOrInsecure) {
  const fs::path dir = TempDir("bind");
  const testing::CommandOutput open = RunGraspsynth("teleop --bind 0.0.0.0 --port 0");
  EXPECT_EQ(open.exit_code, 2);
  EXPECT_NE(open.err.find("--bind 0.0.0.0 opens the link beyond this machine"), std::string::npos)
      << open.err;
  EXPECT_NE(open.err.find("--key-file"), std::string::npos) << open.err;
  const testing::CommandOutput keygen =
      RunGraspsynth("teleop-keygen --out " + (dir / "link.key").string());
  EXPECT_EQ(keygen.exit_code, 0) << keygen.err;
  const testing::CommandOutput again =
      RunGraspsynth("teleop-keygen --out " + (dir / "link.key").string());
  EXPECT_EQ(again.exit_code, 2);
  EXPECT_NE(again.err.find("never overwritten"), std::string::npos) << again.err;
  std::ofstream(dir / "bad.key") << "xyz\n";
  const testing::CommandOutput bad =
      RunGraspsynth("teleop --bind 0.0.0.0 --port 0 --key-file " + (dir / "bad.key").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find((dir / "bad.key").string() + ": line 1"), std::string::npos) << bad.err;
  // with the key, and with --insecure, the server starts (and --exit-after ends it).
  for (const std::string& how :
       {"--key-file " + (dir / "link.key").string(), std::string("--insecure")}) {
    const testing::CommandOutput r =
        RunGraspsynth("teleop --bind 0.0.0.0 --port 0 --orientations 60 --exit-after 0.3 " + how);
    EXPECT_EQ(r.exit_code, 0) << how << ": " << r.err;
    EXPECT_NE(r.err.find(how == "--insecure" ? "Hz (not authenticated" : "Hz (authenticated"),
              std::string::npos)
        << r.err;
  }
  fs::remove_all(dir);
}

// --config is a file of options (graspsynth-options/1) as for every command; the calibration
// file it was before is refused with a message that says where it went, and --calibration takes
// it.
TEST(TeleopCommand, ConfigIsAFileOfOptionsAndACalibrationThereIsRefused) {
  const fs::path dir = TempDir("config");
  const std::string calibration = (dir / "calibration.json").string();
  fs::copy_file(fs::path(::testing::SourceDir()) / "examples" / "teleop_calibration.json",
                calibration);
  const std::string refused =
      "is a teleoperation calibration file (graspsynth-teleop-config/1): the calibration file is "
      "now --calibration FILE";
  const testing::CommandOutput server =
      RunGraspsynth("teleop --port 0 --exit-after 0.1 --config " + calibration);
  EXPECT_EQ(server.exit_code, 2);
  EXPECT_NE(server.err.find("--config '" + calibration + "' " + refused), std::string::npos)
      << server.err;
  const testing::CommandOutput client =
      RunGraspsynth("teleop-client --replay " + calibration + " --config " + calibration);
  EXPECT_EQ(client.exit_code, 2);
  EXPECT_NE(client.err.find(refused), std::string::npos) << client.err;
  // --calibration reads it (a broken one is refused by its name).
  const testing::CommandOutput ok = RunGraspsynth(
      "teleop --port 0 --orientations 60 --exit-after 0.2 --calibration " + calibration);
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  std::ofstream(dir / "broken.json") << R"({"format": "graspsynth-teleop-config/1"})";
  const testing::CommandOutput broken = RunGraspsynth(
      "teleop --port 0 --exit-after 0.1 --calibration " + (dir / "broken.json").string());
  EXPECT_EQ(broken.exit_code, 2);
  EXPECT_NE(broken.err.find((dir / "broken.json").string()), std::string::npos) << broken.err;
  // the options from --config, a flag over the file's rate.
  std::ofstream(dir / "options.json")
      << R"({"format": "graspsynth-options/1", "orientations": [70], "rate": 30, "port": 0,
             "exit_after": 0.2})";
  const testing::CommandOutput options =
      RunGraspsynth("teleop --config " + (dir / "options.json").string() + " --rate 50");
  EXPECT_EQ(options.exit_code, 0) << options.err;
  EXPECT_NE(options.err.find(" at 50 Hz ("), std::string::npos) << options.err;
  EXPECT_NE(options.err.find("theta 70 deg"), std::string::npos) << options.err;
  std::ofstream(dir / "bad.json") << R"({"rate": 5000})";
  const testing::CommandOutput bad =
      RunGraspsynth("teleop --port 0 --config " + (dir / "bad.json").string());
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("field 'rate': must be [1, 1000] (got 5000)"), std::string::npos)
      << bad.err;
  fs::remove_all(dir);
}

TEST(TeleopCommand, SignalEndsTheSessionWithASummary) {
  const fs::path dir = TempDir("signal");
  const pid_t server =
      Spawn({"teleop", "--port", "0", "--port-file", (dir / "port").string(), "--orientations",
             "60", "--summary", (dir / "summary.json").string()});
  for (int k = 0; k < 1500 && !fs::exists(dir / "port"); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(fs::exists(dir / "port"));
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  kill(server, SIGTERM);
  EXPECT_EQ(WaitFor(server, 30.0), 0);
  const nlohmann::json summary = nlohmann::json::parse(testing::ReadFileText(dir / "summary.json"));
  EXPECT_EQ(summary["format"], "graspsynth-teleop-session/1");
  EXPECT_EQ(summary["end"], "signal");
  EXPECT_EQ(summary["packets"]["received"], 0);
  EXPECT_TRUE(summary["trials"].empty());
  fs::remove_all(dir);
}

// Replays `original` (a successful trial at theta_deg) into a recording server and checks that
// the recorded trial has the same outcome and grasp pose.
void ExpectRecordedAgain(const DemoLog& original, const std::string& theta_deg,
                         const std::string& name, bool authenticated = false) {
  const fs::path dir = TempDir(name);
  std::string key_option;  // with `authenticated`, both ends take a new key
  if (authenticated) {
    const std::string key = (dir / "link.key").string();
    ASSERT_EQ(RunGraspsynth("teleop-keygen --out " + key).exit_code, 0);
    key_option = " --key-file " + key;
  }
  const SegmentedTrial original_segmented = Segment(original, SegmentationOptions{});
  ASSERT_TRUE(original_segmented.success);
  WriteDemoLog(dir / "original.csv", original);

  std::vector<std::string> server_args = {"teleop",
                                          "--port",
                                          "0",
                                          "--port-file",
                                          (dir / "port").string(),
                                          "--orientations",
                                          theta_deg,
                                          "--record",
                                          (dir / "recorded").string(),
                                          "--summary",
                                          (dir / "summary.json").string(),
                                          "--exit-after",
                                          "120"};
  if (authenticated)
    server_args.insert(server_args.end(), {"--key-file", (dir / "link.key").string()});
  const pid_t server = Spawn(server_args);
  for (int k = 0; k < 1500 && !fs::exists(dir / "port"); ++k) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(fs::exists(dir / "port")) << "the server did not start";
  const std::string port = testing::ReadFileText(dir / "port");
  // slower under the sanitizers, so that the server keeps its rate.
  const double speed = testing::Scaled(1, 0) == 1 ? 1.0 : 0.5;
  const testing::CommandOutput client = RunGraspsynth(
      "teleop-client --replay " + (dir / "original.csv").string() + " --port " + port +
      " --speed " + (speed == 1.0 ? "1" : "0.5") + " --linger 1.5" + key_option);
  EXPECT_EQ(client.exit_code, 0) << client.err;
  EXPECT_EQ(WaitFor(server, 60.0), 0);

  const nlohmann::json out = nlohmann::json::parse(client.out);
  EXPECT_EQ(out["commands_sent"], original.samples.size());
  // the server answers every tick once the first command came: about 60 per second.
  EXPECT_GT(out["states_received"].get<double>(), 0.8 * 60.0 * original.samples.back().t);
  EXPECT_EQ(out["invalid_received"], 0);

  const nlohmann::json summary = nlohmann::json::parse(testing::ReadFileText(dir / "summary.json"));
  EXPECT_EQ(summary["end"], "end_of_session");
  EXPECT_EQ(summary["authenticated"], authenticated);
  EXPECT_EQ(summary["packets"]["dropped_total"], 0);
  EXPECT_EQ(summary["packets"]["accepted"], original.samples.size() + 3);
  ASSERT_EQ(summary["trials"].size(), 1u) << summary.dump(2);
  const nlohmann::json& trial = summary["trials"][0];
  EXPECT_EQ(trial["outcome"], "success") << trial.dump();
  ASSERT_TRUE(trial["file"].is_string()) << trial.dump();

  const DemoLog recorded = ReadDemoLog(trial["file"].get<std::string>());
  const SegmentedTrial segmented = Segment(recorded, SegmentationOptions{});
  EXPECT_EQ(segmented.success, original_segmented.success);
  EXPECT_GE(segmented.lift, 0.05);
  const size_t g0 = FindEvent(original, DemoEvent::kGrasp).value();
  const size_t g1 = FindEvent(recorded, DemoEvent::kGrasp).value();
  const DemoSample& a = original.samples[g0];
  const DemoSample& b = recorded.samples[g1];
  // the client plays the log at `speed`, so the recorded trial runs 1 / speed times as long.
  EXPECT_NEAR(b.t, a.t / speed, 0.1 / speed);
  EXPECT_LT((b.p_WH - a.p_WH).norm(), 0.01) << b.p_WH.transpose() << " vs " << a.p_WH.transpose();
  EXPECT_LT(AngleBetween(b.q_WH, a.q_WH), 2.0 * M_PI / 180.0);
  EXPECT_LT((b.f - a.f).cwiseAbs().maxCoeff(), 0.05);
  fs::remove_all(dir);
}

TEST(TeleopCommand, AReplayedTrialIsRecordedAgainWithTheSameOutcome) {
  TrialResult nominal;
  const DemoLog original = testing::ScriptedDemoLog(60.0, 60.0, &nominal);
  ASSERT_TRUE(nominal.success()) << nominal.BriefReport();
  ExpectRecordedAgain(original, "60", "loop");
}

TEST(TeleopCommand, AShippedSyntheticTrialIsRecordedAgainOverAnAuthenticatedLink) {
  // a trial of the synthetic operator (learning_data/demos), made by a different path than the
  // scripted grasp: its own rest pose, reach and hook grip. Over a live link the commands reach
  // the server's ticks with some jitter, so the replay is a slightly perturbed trial: the test
  // takes the orientation's representative (score 1.0 in learning_data/library.json), not a
  // marginal one (trial 1 scores 0.7, tilted in 3 of 20 replays, and tilted once in CI).
  const DemoLog original = ReadDemoLog(fs::path(::testing::SourceDir()) / "learning_data" /
                                       "demos" / "theta100_trial08.csv");
  // over an authenticated link (teleop-keygen, --key-file at both ends).
  ExpectRecordedAgain(original, "100", "synthetic", true);
}

// The README's teleoperation example, as written there: a server on a free port (the port file
// tells the client which), a shipped demonstration replayed into it, the recorded trial.
constexpr const char* kReadmeExample =
    R"sh(build/apps/graspsynth teleop --port 0 --port-file teleop.port --orientations 100 \
    --record demos/ --summary session.json &
while [ ! -s teleop.port ]; do sleep 0.1; done
build/apps/graspsynth teleop-client --replay learning_data/demos/theta100_trial08.csv \
    --port "$(cat teleop.port)"
wait
)sh";

TEST(TeleopCommand, TheReadmeExampleRunsAsWritten) {
  if (testing::Scaled(1, 0) != 1) {
    GTEST_SKIP() << "the example replays at the log's own rate, which a sanitized server cannot "
                    "keep (the tests above replay at half speed there)";
  }
  // a fresh clone's layout in a scratch folder: the command at build/apps/graspsynth and the
  // shipped demonstrations, so that the example's own paths work.
  const fs::path dir = TempDir("readme");
  fs::create_directories(dir / "build" / "apps");
  fs::create_symlink(::testing::GraspsynthBinary(), dir / "build" / "apps" / "graspsynth");
  fs::create_symlink(fs::path(::testing::SourceDir()) / "learning_data", dir / "learning_data");
  std::ofstream(dir / "example.sh") << kReadmeExample;
  // under coreutils' timeout, a guard against a hang (it ends the server with the script).
  const std::string command = "cd " + dir.string() + " && timeout -k 10 300 bash example.sh > " +
                              (dir / "out").string() + " 2> " + (dir / "err").string();
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  const std::string err = testing::ReadFileText(dir / "err");
  ASSERT_EQ(WEXITSTATUS(status), 0) << err;  // `wait`: the server's exit status

  // the client's summary on stdout, the server's session summary and the recorded trial.
  const nlohmann::json client = nlohmann::json::parse(testing::ReadFileText(dir / "out"));
  EXPECT_GT(client["states_received"].get<int>(), 0);
  const nlohmann::json summary = nlohmann::json::parse(testing::ReadFileText(dir / "session.json"));
  EXPECT_EQ(summary["end"], "end_of_session");
  ASSERT_EQ(summary["trials"].size(), 1u) << summary.dump(2);
  EXPECT_EQ(summary["trials"][0]["outcome"], "success") << summary["trials"][0].dump();
  const fs::path recorded = dir / "demos" / "trial_001_theta100.csv";
  ASSERT_TRUE(fs::exists(recorded)) << summary["trials"][0].dump();
  EXPECT_TRUE(Segment(ReadDemoLog(recorded), SegmentationOptions{}).success);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace graspsynth
