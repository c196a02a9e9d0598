// Tests of the --robot option every command takes (apps/cli_helpers.hpp's AddRobotOption,
// kinematics/robot_file.hpp's LoadRobotOption): a word that is no shipped robot exits 2 naming
// the shipped robots; the iiwa 14 + Allegro loads, and a command that reads data made for the
// PA-10 + Gifu Hand III (libraries, demonstrations, trajectories) refuses it with exit 2 and a
// message that says so, rather than crashing or playing the PA-10's data on it.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::RunGraspsynth;

struct RobotCase {
  std::string name;   // for the test's name
  std::string args;   // the command line without --robot; {dir} is a fresh folder
  std::string input;  // stdin
  bool iiwa_runs;     // true: --robot iiwa14_allegro exits 0; false: it is refused
};

class RobotOption : public ::testing::TestWithParam<RobotCase> {
 protected:
  std::string Args(const std::string& robot) const {
    std::string args = GetParam().args;
    for (size_t at; (at = args.find("{dir}")) != std::string::npos;) {
      args.replace(at, 5, dir_.path().string());
    }
    for (size_t at; (at = args.find("{src}")) != std::string::npos;) {
      args.replace(at, 5, ::testing::SourceDir());
    }
    return args + " --robot " + robot;
  }
  testing::TestFolder dir_;
};

TEST_P(RobotOption, AnUnknownRobotExits2NamingTheShippedOnes) {
  const testing::CommandOutput r = RunGraspsynth(Args("nosuchrobot"), GetParam().input, 600);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("--robot: expected a shipped robot (iiwa14_allegro, pa10_gifu3;"));
  EXPECT_THAT(r.err, HasSubstr("found \"nosuchrobot\""));
}

TEST_P(RobotOption, TheIiwaLoadsAndRunsOrIsRefusedForThePa10sData) {
  const testing::CommandOutput r = RunGraspsynth(Args("iiwa14_allegro"), GetParam().input, 600);
  if (GetParam().iiwa_runs) {
    EXPECT_EQ(r.exit_code, 0) << r.err;
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr("--robot: "));
    EXPECT_THAT(r.err, HasSubstr("cannot use robot 'iiwa14_allegro' ("));
    EXPECT_THAT(r.err, HasSubstr("made for the PA-10 + Gifu Hand III (pa10_gifu3)"));
  }
}

INSTANTIATE_TEST_SUITE_P(
    EveryCommand, RobotOption,
    ::testing::Values(
        RobotCase{"run", "run --quick --out {dir}/run", "", false},
        RobotCase{"select", "select {dir} --out {dir}/library.json", "", false},
        RobotCase{"synthesize", "synthesize --theta 60 --out {dir}/grasp.json", "", false},
        RobotCase{"generalize", "generalize --orientations 60 --out {dir}/gen", "", false},
        RobotCase{"demos_generate", "demos generate --out {dir}/demos", "", false},
        RobotCase{"demos_calibrate", "demos calibrate --out {dir}/operator.json", "", false},
        RobotCase{"simulate", "simulate {src}/examples/grasp_60deg.json", "", false},
        RobotCase{"scripted_grasp", "scripted-grasp --out {dir}/s.json", "", true},
        RobotCase{"export_mjcf_grasp",
                  "export-mjcf --trajectory {src}/examples/grasp_60deg.json --out {dir}/m.xml", "",
                  false},
        RobotCase{"view_grasp", "view --trajectory {src}/examples/grasp_60deg.json --port 0", "",
                  false},
        RobotCase{"teleop", "teleop --port 0 --exit-after 0.1", "", false},
        RobotCase{"view_at_rest", "view --port 0 --no-wait --exit-after 0.2", "", true},
        RobotCase{"export_mjcf", "export-mjcf --theta 45 --out {dir}/m.xml", "", true},
        RobotCase{"fk", "fk", "0 0 0 0 0 0 0\n", true},
        RobotCase{"ik", "ik",
                  "0.7149281966354228 0 0.7044450552560979 0.5403023058681398 0 "
                  "0.8414709848078965 0 0.3\n",
                  true}),
    [](const ::testing::TestParamInfo<RobotCase>& info) { return info.param.name; });

}  // namespace
}  // namespace graspsynth
