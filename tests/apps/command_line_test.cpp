// Tests of the graspsynth command line itself (apps/main.cpp): --help and --version answer with
// exit status 0; every refusal of a command line (an unknown flag or command, a missing or bad
// value) exits 2, as the README says of bad input, and a misspelt flag or command is answered
// with the nearest one.

#include <gtest/gtest.h>

#include <string>

#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using testing::RunGraspsynth;

TEST(CommandLine, HelpAndVersionExitZero) {
  const testing::CommandOutput version = RunGraspsynth("--version");
  EXPECT_EQ(version.exit_code, 0) << version.err;
  EXPECT_EQ(version.out, "graspsynth 0.1.0\n");
  const testing::CommandOutput help = RunGraspsynth("run --help");
  EXPECT_EQ(help.exit_code, 0) << help.err;
  EXPECT_NE(help.out.find("--select-perturb"), std::string::npos) << help.out;
  EXPECT_NE(RunGraspsynth("version").out.find("graspsynth 0.1.0"), std::string::npos);
}

TEST(CommandLine, AMisspeltFlagExits2WithTheNearestFlag) {
  const testing::CommandOutput r = RunGraspsynth("synthesize --theta 45 --seeed 3 --out x.json");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--seeed"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--seeed: did you mean --seed?"), std::string::npos) << r.err;
  // a flag of another command is not suggested, and a far-off one gets no guess.
  const testing::CommandOutput far = RunGraspsynth("fk --zzzzzzzz");
  EXPECT_EQ(far.exit_code, 2) << far.err;
  EXPECT_EQ(far.err.find("did you mean"), std::string::npos) << far.err;
}

TEST(CommandLine, AnUnknownCommandExits2WithTheNearestCommand) {
  const testing::CommandOutput r = RunGraspsynth("synthesise --theta 45");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("'synthesise' is not a command (did you mean 'synthesize'?)"),
            std::string::npos)
      << r.err;
  const testing::CommandOutput nothing_near = RunGraspsynth("frobnicate");
  EXPECT_EQ(nothing_near.exit_code, 2);
  EXPECT_NE(nothing_near.err.find("'frobnicate' is not a command; 'graspsynth --help' lists"),
            std::string::npos)
      << nothing_near.err;
}

TEST(CommandLine, AMissingCommandFlagOrValueExits2) {
  EXPECT_EQ(RunGraspsynth("").exit_code, 2);                    // no command
  EXPECT_EQ(RunGraspsynth("generalize").exit_code, 2);          // --out is required
  EXPECT_EQ(RunGraspsynth("synthesize --theta").exit_code, 2);  // a flag without its value
  EXPECT_EQ(RunGraspsynth("run --seed many").exit_code, 2);     // not a number
  EXPECT_EQ(RunGraspsynth("demos").exit_code, 2);               // generate or calibrate
}

}  // namespace
}  // namespace graspsynth
