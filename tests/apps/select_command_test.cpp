// Tests of `graspsynth select` through the built binary, on a temporary folder of logs made
// from the scripted grasp.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "common/data_dir.hpp"
#include "learning_data/grasp_library.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/scripted_demos.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadFileText;
using testing::RunGraspsynth;
using testing::ShippedSimulationModel;

TEST(SelectCommand, SelectsPerOrientationWritesTheLibraryAndNamesTheBadFile) {
  const testing::TestFolder folder;
  const auto demos = folder.path() / "demos";
  std::filesystem::create_directories(demos);
  for (double theta : {40.0, 80.0}) {
    const std::string name = "demo_0" + std::to_string(static_cast<int>(theta)) + ".csv";
    WriteDemoLog(demos / name, testing::ScriptedDemoLog(ShippedSimulationModel(), theta, name));
  }
  std::ofstream(demos / "broken.csv") << "not a log\n";
  const auto out = folder.path() / "out" / "library.json";
  const int perturb = testing::Scaled(3, 1);
  const auto r = RunGraspsynth("select " + demos.string() + " --out " + out.string() +
                               " --perturb " + std::to_string(perturb) + " --seed 5 --threads 2");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("read 2 demonstration log(s)"));
  EXPECT_THAT(r.out, HasSubstr("(1 rejected)"));
  EXPECT_THAT(r.out, HasSubstr("theta_deg"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex("40.00 +1 +demo_040.csv"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex("80.00 +1 +demo_080.csv"));
  EXPECT_THAT(r.out, HasSubstr("broken.csv (unreadable)"));
  EXPECT_THAT(r.out, HasSubstr("wrote " + out.string() + ": 2 orientation(s) selected"));
  EXPECT_THAT(r.err, HasSubstr("rejected broken.csv"));
  EXPECT_THAT(r.err, HasSubstr("replays"));

  const GraspLibrary library = ReadGraspLibrary(out);
  EXPECT_EQ(library.seed, 5u);
  EXPECT_EQ(library.perturbations, perturb);
  ASSERT_EQ(library.entries.size(), 2u);
  EXPECT_EQ(library.entries[0].theta_deg, 40.0);
  EXPECT_EQ(library.entries[1].file, "demo_080.csv");
  const json j = json::parse(ReadFileText(out));
  EXPECT_EQ(j.at("format"), "graspsynth-library/1");

  // one thread, the options from --config and a flag over the file's seed: the same bytes.
  const auto config = folder.path() / "select.json";
  std::ofstream(config) << R"({"perturb": )" << perturb << R"(, "seed": 9, "all_replays": false})";
  const auto out1 = folder.path() / "out" / "library1.json";
  const auto r1 = RunGraspsynth("select " + demos.string() + " --out " + out1.string() +
                                " --config " + config.string() + " --seed 5 --threads 1");
  EXPECT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_EQ(ReadFileText(out), ReadFileText(out1));
}

// Logs at two object positions (from the shipped placements set): one representative per
// placement, a version-2 library whose entries carry their placements.
TEST(SelectCommand, LogsAtSeveralPositionsAreSelectedPerPlacement) {
  const testing::TestFolder folder;
  const auto demos = folder.path() / "demos";
  std::filesystem::create_directories(demos);
  const auto shipped = DataDirectory() / "learning_data" / "placements" / "demos";
  for (const char* name :
       {"x-0250_y+0850_theta060_trial01.csv", "x-0190_y+0910_theta060_trial01.csv",
        "x-0190_y+0910_theta060_trial03.csv"}) {
    std::filesystem::copy_file(shipped / name, demos / name);
  }
  const auto out = folder.path() / "library.json";
  const auto r = RunGraspsynth("select " + demos.string() + " --out " + out.string() +
                               " --perturb 3 --threads 2");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, ::testing::ContainsRegex("-0.190 +0.910 +60.00 +2 +x-0190_y"));
  EXPECT_THAT(r.out, ::testing::ContainsRegex("-0.250 +0.850 +60.00 +1 +x-0250_y"));
  EXPECT_THAT(r.out, HasSubstr(": 2 placement(s) selected"));
  const json j = json::parse(ReadFileText(out));
  EXPECT_EQ(j.at("format"), "graspsynth-library/2");
  ASSERT_EQ(j.at("entries").size(), 2u);
  // sorted by x, then y, then theta; each with its placement.
  EXPECT_NEAR(j["entries"][0]["placement"]["x"].get<double>(), -0.25, 1e-12);
  EXPECT_EQ(j["entries"][1]["placement"]["theta_deg"], 60.0);
  EXPECT_NEAR(j["entries"][1]["placement"]["y"].get<double>(), 0.91, 1e-12);
  const GraspLibrary library = ReadGraspLibrary(out);
  EXPECT_TRUE(library.HasPositions());
}

TEST(SelectCommand, AllReplaysPicksTheSameRepresentativeAndStopsNoDemonstration) {
  const testing::TestFolder folder;
  const auto demos = folder.path() / "demos";
  std::filesystem::create_directories(demos);
  WriteDemoLog(demos / "demo_040_a.csv",
               testing::ScriptedDemoLog(ShippedSimulationModel(), 40.0, "demo_040_a.csv"));
  ScriptedGraspOptions other;
  other.theta_deg = 40.0;
  other.grasp_radius = 0.13;
  WriteDemoLog(demos / "demo_040_b.csv",
               testing::ScriptedDemoLog(ShippedSimulationModel(), other, "demo_040_b.csv"));
  const std::string perturb = " --perturb " + std::to_string(testing::Scaled(3, 1));
  const auto early_out = folder.path() / "early.json";
  const auto all_out = folder.path() / "all.json";
  const auto early =
      RunGraspsynth("select " + demos.string() + " --out " + early_out.string() + perturb);
  const auto all = RunGraspsynth("select " + demos.string() + " --out " + all_out.string() +
                                 perturb + " --all-replays");
  ASSERT_EQ(early.exit_code, 0) << early.err;
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const json e = json::parse(ReadFileText(early_out));
  const json a = json::parse(ReadFileText(all_out));
  EXPECT_EQ(e.at("entries"), a.at("entries"));
  int stopped = 0;
  for (size_t i = 0; i < a.at("scores").size(); ++i) {
    EXPECT_FALSE(a["scores"][i].contains("stopped"));
    if (e["scores"][i].contains("stopped")) {
      ++stopped;
      EXPECT_FALSE(e["scores"][i].at("selected").get<bool>());
    } else {
      EXPECT_EQ(e["scores"][i], a["scores"][i]);
    }
  }
  // the summary says how many replays ran when a demonstration stopped.
  EXPECT_EQ(stopped > 0, early.out.find("perturbed replays ran") != std::string::npos) << early.out;
  EXPECT_THAT(all.out, Not(HasSubstr("perturbed replays ran")));
  EXPECT_THAT(RunGraspsynth("select --help").out, HasSubstr("--all-replays"));
}

TEST(SelectCommand, FailsWhenNoOrientationCanBeSelected) {
  const testing::TestFolder folder;
  DemoLog log = testing::ScriptedDemoLog(ShippedSimulationModel(), 60.0, "demo_060.csv");
  for (DemoSample& s : log.samples) s.p_WO = log.samples.front().p_WO;  // the pan never rose
  WriteDemoLog(folder.path() / "demo_060.csv", log);
  const auto out = folder.path() / "library.json";
  const auto r =
      RunGraspsynth("select " + folder.path().string() + " --out " + out.string() + " --perturb 1");
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("1 unsuccessful (skipped)"));
  EXPECT_THAT(r.err, HasSubstr("no orientation could be selected"));
  // the library is written all the same, empty.
  EXPECT_TRUE(ReadGraspLibrary(out).entries.empty());
}

TEST(SelectCommand, RejectsBadInputAndExplainsItself) {
  const auto help = RunGraspsynth("select --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_THAT(help.out, HasSubstr("graspsynth-library/1"));
  EXPECT_THAT(help.out, HasSubstr("ties go to"));
  EXPECT_THAT(help.out, HasSubstr("--perturb"));
  EXPECT_THAT(help.out, HasSubstr("whatever --threads is"));
  const testing::TestFolder folder;
  const auto missing =
      RunGraspsynth("select /nonexistent/folder --out " + (folder.path() / "x.json").string());
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_THAT(missing.err, HasSubstr("/nonexistent/folder"));
  EXPECT_FALSE(std::filesystem::exists(folder.path() / "x.json"));
  const auto zero = RunGraspsynth("select " + folder.path().string() + " --out " +
                                  (folder.path() / "l.json").string() + " --perturb 0");
  EXPECT_NE(zero.exit_code, 0);
  EXPECT_THAT(zero.err, HasSubstr("--perturb: must be >= 1 (got 0)"));
  EXPECT_THAT(zero.err, Not(HasSubstr("1797693")));  // not the whole range of a double
  const auto config = folder.path() / "bad.json";
  std::ofstream(config) << R"({"pertrub": 2})";
  const auto typo =
      RunGraspsynth("select " + folder.path().string() + " --out " +
                    (folder.path() / "l.json").string() + " --config " + config.string());
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_THAT(typo.err, HasSubstr("field 'pertrub' is not an option"));
  EXPECT_THAT(typo.err, HasSubstr("did you mean 'perturb'?"));
}

}  // namespace
}  // namespace graspsynth
