// Tests of `graspsynth demos`: generate writes a readable, physics-labelled set and the config
// that made it; calibrate writes a valid operator file; bad input is a clear error.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "learning_data/demo_directory.hpp"
#include "learning_data/synthetic_operator.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using testing::RunGraspsynth;

fs::path TempDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("graspsynth_demos_" + std::to_string(::getpid()) + "_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The shipped operator reduced to one orientation (theta 90).
fs::path SmallConfig(const fs::path& dir) {
  OperatorOptions options = ReadOperatorOptions(DefaultOperatorOptionsPath());
  std::vector<OrientationPlan> plans;
  for (const OrientationPlan& p : options.plans) {
    if (p.theta_deg == 90.0) plans.push_back(p);
  }
  options.plans = plans;
  const fs::path path = dir / "small.json";
  WriteOperatorOptions(options, path);
  return path;
}

TEST(DemosCommand, GenerateWritesLogsAndTheirConfig) {
  const fs::path dir = TempDir("generate");
  const fs::path config = SmallConfig(dir);
  const testing::CommandOutput r =
      RunGraspsynth("demos generate --operator " + config.string() + " --out " +
                    (dir / "out").string() + " --trials-per-orientation 2 --seed 5 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote 2 logs"));
  const DemoDirectory demos = ReadDemoDirectory(dir / "out");
  EXPECT_EQ(demos.logs.size(), 2u);
  EXPECT_TRUE(demos.rejected.empty());
  EXPECT_EQ(demos.logs.front().metadata.theta_deg, 90.0);
  // the config written beside the logs makes them again: seed and trial count included.
  const OperatorOptions used = ReadOperatorOptions(dir / "out" / "operator.json");
  EXPECT_EQ(used.seed, 5u);
  EXPECT_EQ(used.trials_per_orientation, 2);
  fs::remove_all(dir);
}

TEST(DemosCommand, CalibrateWritesAValidOperator) {
  const fs::path dir = TempDir("calibrate");
  const fs::path config = SmallConfig(dir);
  const testing::CommandOutput r = RunGraspsynth(
      "demos calibrate --operator " + config.string() + " --out " +
      (dir / "calibrated.json").string() + " --trials-per-orientation 2 --iterations 1 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const OperatorOptions calibrated = ReadOperatorOptions(dir / "calibrated.json");
  ASSERT_EQ(calibrated.plans.size(), 1u);
  EXPECT_EQ(calibrated.plans.front().theta_deg, 90.0);
  fs::remove_all(dir);
}

// Another object's shipped operator makes trials that physics labels; its summary has no
// column of the paper's Table I, and calibrating to that table is refused.
TEST(DemosCommand, AnotherObjectIsNotComparedWithThePaper) {
  const fs::path dir = TempDir("saucepan");
  OperatorOptions options = ReadOperatorOptions(DefaultOperatorOptionsPath("saucepan"));
  options.plans.resize(1);  // 20 deg
  WriteOperatorOptions(options, dir / "small.json");
  const testing::CommandOutput r =
      RunGraspsynth("demos generate --object saucepan --operator " + (dir / "small.json").string() +
                    " --out " + (dir / "out").string() + " --trials-per-orientation 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("wrote 2 logs"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("paper")));
  const testing::CommandOutput c =
      RunGraspsynth("demos calibrate --object saucepan --operator " +
                    (dir / "small.json").string() + " --out " + (dir / "c.json").string());
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_THAT(c.err, HasSubstr("'saucepan' is not the paper's pan"));
  EXPECT_FALSE(fs::exists(dir / "c.json"));
  fs::remove_all(dir);
}

TEST(DemosCommand, ConfigIsAFileOfOptionsAndAnOperatorFileThereIsRefused) {
  const fs::path dir = TempDir("options");
  const fs::path config = SmallConfig(dir);
  // --config sets the options (seed, trials) over the operator file's; the flags override it.
  std::ofstream(dir / "options.json") << R"({"seed": 9, "trials_per_orientation": 3})";
  testing::CommandOutput r =
      RunGraspsynth("demos generate --operator " + config.string() + " --config " +
                    (dir / "options.json").string() + " --trials-per-orientation 1 --quiet --out " +
                    (dir / "out").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const OperatorOptions used = ReadOperatorOptions(dir / "out" / "operator.json");
  EXPECT_EQ(used.seed, 9u);
  EXPECT_EQ(used.trials_per_orientation, 1);
  // the operator file where the options go: refused, saying where it went.
  r = RunGraspsynth("demos generate --config " + config.string() + " --out " +
                    (dir / "out2").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("is an operator file (graspsynth-operator/1): the operator file "
                               "is now --operator FILE"));
  r = RunGraspsynth("demos calibrate --config " + config.string() + " --out " +
                    (dir / "c.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--operator FILE"));
  // a seed out of range, or an option of the other subcommand, named.
  std::ofstream(dir / "bad.json") << R"({"damping": 0.5})";
  r = RunGraspsynth("demos generate --config " + (dir / "bad.json").string() + " --out " +
                    (dir / "out3").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("field 'damping' is not an option of this command"));
  r = RunGraspsynth("demos calibrate --damping 2 --out " + (dir / "c.json").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--damping: must be [0.05, 1] (got 2)"));
  EXPECT_FALSE(fs::exists(dir / "out3"));
  fs::remove_all(dir);
}

TEST(DemosCommand, BadConfigIsAnErrorNamingTheFile) {
  const fs::path dir = TempDir("bad");
  std::ofstream(dir / "bad.json") << R"({"format": "graspsynth-operator/1"})";
  const testing::CommandOutput r =
      RunGraspsynth("demos generate --operator " + (dir / "bad.json").string() + " --out " +
                    (dir / "out").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("bad.json"));
  EXPECT_THAT(r.err, HasSubstr("plans"));
  EXPECT_FALSE(fs::exists(dir / "out"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace graspsynth
