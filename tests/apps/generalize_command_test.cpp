// Tests of `graspsynth generalize`: a small table end to end on the shipped library, the
// leave-one-out mode, and bad options (each an error that writes nothing).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileText;
using testing::RunGraspsynth;

class GeneralizeCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("graspsynth_generalize_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> CsvLines(const std::string& name) const {
    std::vector<std::string> lines;
    std::istringstream in(ReadFileText(dir_ / (name + ".csv")));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  fs::path dir_;
};

TEST_F(GeneralizeCommand, WritesOneRowPerOrientationAndMethod) {
  const testing::CommandOutput r = RunGraspsynth(
      "generalize --orientations 60:70:10 --methods interp,nearest --perturb 1 --threads 2 "
      "--name g --out " +
      dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = CsvLines("g");
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0].rfind("theta_deg,method,status", 0), 0u);
  EXPECT_EQ(lines[1].rfind("60,interp,ok,interp,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("60,nearest,ok,nearest,", 0), 0u) << lines[2];
  EXPECT_EQ(lines[3].rfind("70,interp,ok,", 0), 0u) << lines[3];
  const std::string md = ReadFileText(dir_ / "g.md");
  EXPECT_NE(md.find("| interp | 2 | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("## Where a method falls short"), std::string::npos);
  EXPECT_NE(r.out.find("interp: "), std::string::npos) << r.out;
}

TEST_F(GeneralizeCommand, AConfigFileGivesWhatItsFlagsGiveAndTheFlagsOverrideIt) {
  fs::create_directories(dir_);
  const fs::path config = dir_ / "options.json";
  std::ofstream(config) << R"({"orientations": [60], "methods": ["nearest"], "perturb": 2,
                              "seed": 5, "physics": false, "noise_scale": 0.5})";
  const std::string out = " --out " + dir_.string();
  testing::CommandOutput r = RunGraspsynth(
      "generalize --orientations 60 --methods nearest --perturb 2 --seed 5 --physics off "
      "--noise-scale 0.5 --name flags" +
      out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = RunGraspsynth("generalize --config " + config.string() + " --name config" + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(CsvLines("config"), CsvLines("flags"));
  // a flag after the file wins: another seed gives other replays
  r = RunGraspsynth("generalize --config " + config.string() + " --seed 6 --name seed6" + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(ReadFileText(dir_ / "seed6.md").find("Seed 6,"), std::string::npos);
  std::ofstream(config) << R"({"pertrub": 2})";
  r = RunGraspsynth("generalize --config " + config.string() + " --name bad" + out);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("field 'pertrub' is not an option of this command (did you mean "
                       "'perturb'?)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "bad.csv"));
}

TEST_F(GeneralizeCommand, ABlendThatFailsInPhysicsFallsBackUnlessTold) {
  // the shipped 60 and 70 deg representatives blend into a grasp that drops the pan at 65 deg.
  const std::string common = "generalize --orientations 65 --methods interp+refine --perturb 0 ";
  testing::CommandOutput r = RunGraspsynth(common + "--name on --out " + dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::vector<std::string> lines = CsvLines("on");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1].rfind("65,interp+refine,ok,nearest,1,1,1,success,", 0), 0u) << lines[1];
  EXPECT_NE(ReadFileText(dir_ / "on.md").find("its blend failed its nominal trial in physics"),
            std::string::npos);

  r = RunGraspsynth(common + "--no-physics-fallback --name off --out " + dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  lines = CsvLines("off");
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1].rfind("65,interp+refine,ok,interp,0,1,0,", 0), 0u) << lines[1];
}

TEST_F(GeneralizeCommand, LeaveOneOutSynthesizesEachInnerOrientationWithoutIt) {
  const testing::CommandOutput r = RunGraspsynth(
      "generalize --leave-one-out --methods interp --perturb 0 --name loo --out " + dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = CsvLines("loo");
  // the shipped library holds 20, 30, ..., 100 deg: 30..90 are inner.
  ASSERT_EQ(lines.size(), 8u);
  for (int k = 0; k < 7; ++k) {
    const std::string theta = std::to_string(30 + 10 * k);
    EXPECT_EQ(lines[k + 1].rfind(theta + ",interp,ok,", 0), 0u) << lines[k + 1];
    // without its own demonstration, an inner orientation is a blend of its neighbours from
    // 70 deg on; below, the shipped neighbours hold the handle too differently to blend (more
    // than 60 deg apart, or from both sides of it), and the nearer one is used, said why.
    std::vector<std::string> f;
    std::istringstream in(lines[k + 1]);
    for (std::string field; std::getline(in, field, ',');) f.push_back(field);
    ASSERT_GT(f.size(), 4u);
    const bool blended = 30 + 10 * k >= 70;
    EXPECT_EQ(f[3], blended ? "interp" : "nearest") << lines[k + 1];
    EXPECT_EQ(f[4], blended ? "0" : "1") << lines[k + 1];
    if (!blended) {
      EXPECT_NE(ReadFileText(dir_ / "loo.md")
                    .find("- " + theta +
                          " deg, interp used nearest: the "
                          "bracket"),
                std::string::npos)
          << theta;
    }
  }
}

TEST_F(GeneralizeCommand, AGridOfPositionsGivesEveryOrientationAtEveryPosition) {
  const testing::CommandOutput r = RunGraspsynth(
      "generalize --x -0.26,-0.24 --y 0.85 --orientations 60 --methods nearest --perturb 1 "
      "--threads 2 --name g --out " +
      dir_.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> lines = CsvLines("g");
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0].rfind("x,y,theta_deg,method,status", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("-0.26,0.85,60,nearest,ok,", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("-0.24,0.85,60,nearest,ok,", 0), 0u) << lines[2];
  EXPECT_NE(ReadFileText(dir_ / "g.md").find("60 @ (-0.26, 0.85)"), std::string::npos);
}

TEST_F(GeneralizeCommand, BadOptionsAreNamedAndWriteNothing) {
  const std::string out = " --out " + dir_.string();
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--methods interp+polish", "'+polish' is not known"},
           {"--methods interp,interp", "given twice"},
           {"--orientations 30:20:1", "needs FROM <= TO"},
           {"--orientations 20,abc", "'abc' is not a finite number"},
           {"--noise-scale -1", "--noise-scale: must be >= 0 (got -1)"},
           {"--x -0.3", "x and y go together"},
           {"--x a --y 0.8", "--x: 'a' is not a finite number of metres"},
           {"--x -0.3 --y 5", "(-0.3, 5) m is not on the table"},
           {"--x -0.3 --y 0.8 --leave-one-out", "it takes no x or y"},
       }) {
    const testing::CommandOutput r = RunGraspsynth("generalize " + args + out);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "generalization.csv")) << args;
  }
}

// The library must keep an inner orientation once one is left out: one check, in the library
// (LeaveOneOutTable), with the library's file in its words, for the command and for Python.
TEST_F(GeneralizeCommand, LeaveOneOutOfATwoEntryLibraryNamesTheLibrary) {
  fs::create_directories(dir_);
  nlohmann::json library = nlohmann::json::parse(
      ReadFileText(fs::path(::testing::SourceDir()) / "learning_data" / "library.json"));
  library["entries"].erase(library["entries"].begin() + 1, library["entries"].end() - 1);
  const fs::path two = dir_ / "two.json";
  std::ofstream(two) << library.dump();
  const testing::CommandOutput r = RunGraspsynth("generalize --leave-one-out --library " +
                                                 two.string() + " --out " + dir_.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("leave-one-out needs a library with at least 3 orientations ('" +
                       two.string() + "' has 2)"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "generalization.csv"));
}

}  // namespace
}  // namespace graspsynth
