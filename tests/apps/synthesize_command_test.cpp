// Tests of `graspsynth synthesize`: the command end to end on a library file of scripted
// grasps, and its bad queries (each an error that writes nothing).

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/data_dir.hpp"
#include "learning_data/grasp_library.hpp"
#include "tests/solver/synthesis_fixtures.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using testing::ReadFileText;
using testing::RunGraspsynth;

class SynthesizeCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    std::replace(test.begin(), test.end(), '/', '_');  // a parameterised test's "Name/0"
    dir_ =
        fs::temp_directory_path() / ("graspsynth_synth_" + std::to_string(::getpid()) + "_" + test);
    fs::create_directories(dir_);
    library_ = (dir_ / "library.json").string();
    WriteGraspLibrary(testing::Library406080(), library_);
    out_ = (dir_ / "grasp.json").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Args(const std::string& more) const {
    return "synthesize --library " + library_ + " --out " + out_ + " --perturb 2 --threads 2 " +
           more;
  }

  fs::path dir_;
  std::string library_, out_;
};

TEST_F(SynthesizeCommand, WritesAValidatedGraspFileThatSimulatePlays) {
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 50"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(out_)) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_EQ(j["format"], "graspsynth-grasp/1");
  EXPECT_EQ(j["method"]["requested"], "interp");
  EXPECT_TRUE(j["validation"]["passed"].get<bool>());
  EXPECT_EQ(j["validation"]["robustness"]["trials"], 2);
  const std::string report = (dir_ / "report.json").string();
  const testing::CommandOutput sim = RunGraspsynth("simulate " + out_ + " --out " + report);
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_TRUE(nlohmann::json::parse(ReadFileText(report))["nominal"]["success"].get<bool>());
}

// Every other shipped object: with --object NAME the default library is that object's own
// (learning_data/objects/NAME/library.json); at an orientation it has no demonstration of
// (65 deg) the grasp passes the gate, and simulate lifts the object again with it. Not every
// orientation's does: the mug's at 45 deg held 7 of 10 perturbed replays (it swings about the
// pinch when the hand's friction is low; experiments/results/objects.md has every orientation's).
class ShippedObjectGrasp : public SynthesizeCommand,
                           public ::testing::WithParamInterface<std::string> {};

TEST_P(ShippedObjectGrasp, PassesTheGateAndLiftsAgain) {
  const std::string object = GetParam();
  const testing::CommandOutput r = RunGraspsynth(
      "synthesize --object " + object + " --theta 65 --out " + out_ + " --perturb 2 --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_TRUE(j["validation"]["passed"].get<bool>());
  const std::string report = (dir_ / "report.json").string();
  const testing::CommandOutput sim =
      RunGraspsynth("simulate " + out_ + " --object " + object + " --out " + report);
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  EXPECT_TRUE(nlohmann::json::parse(ReadFileText(report))["nominal"]["success"].get<bool>());
}

INSTANTIATE_TEST_SUITE_P(SynthesizeCommand, ShippedObjectGrasp,
                         ::testing::Values("saucepan", "sugar_box", "mug"),
                         [](const auto& info) { return info.param; });

TEST_F(SynthesizeCommand, AtPutsTheObjectElsewhereAndRefusesAPlaceOffTheTable) {
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 50 --at -0.27,0.87 --no-refine"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_EQ(j["object_xy"], nlohmann::json::array({-0.27, 0.87}));
  EXPECT_EQ(j["trajectory"]["object_xy"], nlohmann::json::array({-0.27, 0.87}));
  fs::remove(out_);
  for (const auto& [at, expected] : std::vector<std::pair<std::string, std::string>>{
           {"5,5", "(5, 5) m is not on the table"},
           {"-0.27", "--at: '-0.27' needs X,Y (2 numbers), got 1"},
           {"-0.27,nan", "--at: 'nan' in '-0.27,nan' is not a finite number"},
       }) {
    const testing::CommandOutput bad = RunGraspsynth(Args("--theta 50 --at " + at));
    EXPECT_EQ(bad.exit_code, 2) << at << ": " << bad.err;
    EXPECT_NE(bad.err.find(expected), std::string::npos) << at << ": " << bad.err;
    EXPECT_FALSE(fs::exists(out_)) << at;
  }
}

// The issue's check: the shipped library over placements gives a grasp at a placement it was
// not shown (-0.27, 0.87 m, 65 deg, inside the grid) that passes the gate, and simulate lifts
// the pan with it again, where the grasp file puts it.
TEST_F(SynthesizeCommand, TheShippedPlacementsLibraryGraspsAHeldOutPlacement) {
  const std::string library =
      (DataDirectory() / "learning_data" / "placements" / "library.json").string();
  const testing::CommandOutput r =
      RunGraspsynth("synthesize --library " + library + " --at -0.27,0.87 --theta 65 --out " +
                    out_ + " --perturb " + std::to_string(testing::Scaled(10, 2)) + " --threads 2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_TRUE(j["validation"]["passed"].get<bool>()) << j["validation"].dump();
  EXPECT_EQ(j["object_xy"], nlohmann::json::array({-0.27, 0.87}));
  const std::string report = (dir_ / "report.json").string();
  const testing::CommandOutput sim = RunGraspsynth("simulate " + out_ + " --out " + report);
  EXPECT_EQ(sim.exit_code, 0) << sim.err;
  const nlohmann::json played = nlohmann::json::parse(ReadFileText(report));
  EXPECT_TRUE(played["nominal"]["success"].get<bool>()) << played["nominal"].dump();
  EXPECT_EQ(played["object_xy"], nlohmann::json::array({-0.27, 0.87}));
}

// --grip-slide: at 28 deg the placements library's grasps hold the pan's handle at its end (the
// grip about 37 cm out on a handle that ends at 38 cm); the slide moves it in, the file says by
// how much, and the slid grasp lifts the pan.
TEST_F(SynthesizeCommand, GripSlideMovesAGripAtTheHandlesEndInward) {
  const std::string library =
      (DataDirectory() / "learning_data" / "placements" / "library.json").string();
  const testing::CommandOutput r =
      RunGraspsynth("synthesize --library " + library + " --at -0.25,0.85 --theta 28 " +
                    "--grip-slide --perturb 0 --out " + out_);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("grip slide: the grip held the handle"));
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  const nlohmann::json& slide = j["refinement"]["grip_slide"];
  EXPECT_GT(slide["grip_radius_m"].get<double>(), 0.34) << slide.dump();
  EXPECT_GT(slide["slid_m"].get<double>(), 0.0) << slide.dump();
  EXPECT_TRUE(j["validation"]["passed"].get<bool>()) << j["validation"].dump();

  // without the flag the file has no grip_slide, and --no-refine refuses the flag.
  ASSERT_EQ(RunGraspsynth("synthesize --library " + library +
                          " --at -0.25,0.85 --theta 28 --perturb 0 --out " + out_)
                .exit_code,
            0);
  EXPECT_FALSE(nlohmann::json::parse(ReadFileText(out_))["refinement"].contains("grip_slide"));
  const testing::CommandOutput bad =
      RunGraspsynth("synthesize --library " + library +
                    " --at -0.25,0.85 --theta 28 --grip-slide --no-refine --out " + out_ + "x");
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_THAT(bad.err, ::testing::HasSubstr("grip_slide needs the refinement"));
}

TEST_F(SynthesizeCommand, LineMethodGoesBeyondTheRange) {
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 100 --method line --no-refine"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_EQ(j["method"]["used"], "line");
  EXPECT_FALSE(j["refinement"]["refined"].get<bool>());
}

TEST_F(SynthesizeCommand, InterpOutsideTheRangeIsAnErrorThatSuggestsLine) {
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 100"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("[40, 80]"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("line"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(SynthesizeCommand, BadStartIsAnError) {
  const testing::CommandOutput limits = RunGraspsynth(Args("--theta 50 --start 0,0,0,9,0,0,0"));
  EXPECT_EQ(limits.exit_code, 2);
  EXPECT_NE(limits.err.find("joint 4"), std::string::npos) << limits.err;
  const testing::CommandOutput count = RunGraspsynth(Args("--theta 50 --start 0,0,0"));
  EXPECT_EQ(count.exit_code, 2);
  EXPECT_NE(count.err.find("7"), std::string::npos) << count.err;
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(SynthesizeCommand, ABadHoldMarginThresholdIsAnError) {
  for (const char* flags :
       {"--max-slip-mm -1", "--max-friction-use-mean 0", "--max-slip-deg 181"}) {
    const testing::CommandOutput bad = RunGraspsynth(Args(std::string("--theta 50 ") + flags));
    EXPECT_EQ(bad.exit_code, 2) << flags << ": " << bad.err;
    EXPECT_NE(bad.err.find(std::string(flags).substr(0, std::string(flags).find(' '))),
              std::string::npos)
        << bad.err;
  }
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(SynthesizeCommand, WrongVersionAndCorruptLibrariesAreErrors) {
  std::string text = ReadFileText(library_);
  const size_t at = text.find("graspsynth-library/1");
  ASSERT_NE(at, std::string::npos);
  std::string other = text;
  other.replace(at, 20, "graspsynth-library/9");
  std::ofstream(library_) << other;
  const testing::CommandOutput version = RunGraspsynth(Args("--theta 50"));
  EXPECT_EQ(version.exit_code, 2);
  EXPECT_NE(version.err.find("library.json"), std::string::npos) << version.err;
  std::ofstream(library_) << text.substr(0, text.size() / 2);
  const testing::CommandOutput corrupt = RunGraspsynth(Args("--theta 50"));
  EXPECT_EQ(corrupt.exit_code, 2);
  EXPECT_NE(corrupt.err.find("library.json"), std::string::npos) << corrupt.err;
  const testing::CommandOutput missing = RunGraspsynth(
      "synthesize --library " + (dir_ / "none.json").string() + " --theta 50 --out " + out_);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_FALSE(fs::exists(out_));
}

// A library whose selection kept no orientation is a valid file (select writes it), but there is
// nothing to synthesize from: the error names the file and the field, and writes nothing.
TEST_F(SynthesizeCommand, LibraryWithoutEntriesIsAnErrorNamingTheFile) {
  GraspLibrary empty = testing::Library406080();
  empty.entries.clear();
  WriteGraspLibrary(empty, library_);
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 50"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, ::testing::HasSubstr(library_ + ": entries: the grasp library has no entry"));
  EXPECT_FALSE(fs::exists(out_));
}

// An object without a handle is refused before any work: the synthesis aims at the handle.
TEST_F(SynthesizeCommand, ObjectWithoutAHandleIsRefusedUpFront) {
  const std::string box = (dir_ / "box.json").string();
  std::ofstream(box) << R"({"format": "graspsynth-object/1", "name": "sugar_box", "parts": [)"
                     << R"({"name": "b", "type": "box", "size": [0.038, 0.089, 0.175],)"
                     << R"( "mass": 0.514}]})";
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 50 --object " + box));
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("object 'sugar_box' (" + box +
                                          ") has no handle, and the synthesis"));
  EXPECT_FALSE(fs::exists(out_));
}

TEST_F(SynthesizeCommand, GraspBelowTheGateIsNotWrittenUnlessForced) {
  // a library whose grasps hold the hand 5 cm too high: nothing is lifted.
  ScriptedGraspOptions high;
  high.bar_in_hand = RobotGraspOf(testing::ShippedSimulationModel().robot()).bar_in_hand;
  high.bar_in_hand->x() -= 0.05;
  WriteGraspLibrary(
      testing::ScriptedLibrary(testing::ShippedSimulationModel().robot(),
                               testing::ShippedSimulationModel().scene(), {40.0, 60.0}, +1, high),
      library_);
  const testing::CommandOutput r = RunGraspsynth(Args("--theta 50 --no-refine"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("physics gate"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out_));
  const testing::CommandOutput forced = RunGraspsynth(Args("--theta 50 --no-refine --force"));
  EXPECT_EQ(forced.exit_code, 1) << forced.err;
  ASSERT_TRUE(fs::exists(out_));
  const nlohmann::json j = nlohmann::json::parse(ReadFileText(out_));
  EXPECT_FALSE(j["validation"]["passed"].get<bool>());
  EXPECT_TRUE(j["validation"]["forced"].get<bool>());
}

}  // namespace
}  // namespace graspsynth
