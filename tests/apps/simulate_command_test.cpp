// Tests of `graspsynth simulate` and `graspsynth scripted-grasp` through the built binary.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;
using testing::ReadFileText;
using testing::RunGraspsynth;

std::string Example() { return std::string(::testing::SourceDir()) + "/examples/grasp_60deg.json"; }

// A scratch folder per test.
class SimulateCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("graspsynth_simulate_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  // The example with one change made by `edit`, written to `name`.
  std::string EditedExample(const std::string& name, const std::function<void(json&)>& edit) {
    json doc = json::parse(ReadFileText(Example()));
    edit(doc);
    std::ofstream(Path(name)) << doc.dump();
    return Path(name);
  }

  fs::path dir_;
};

// The physics perturbation, the hold quality and the sensitivity table reach the report.
TEST_F(SimulateCommand, ReportsPhysicsHoldAndSensitivity) {
  const auto r =
      RunGraspsynth("simulate " + Example() + " --perturb 2 --sensitivity 1 --threads 2 --out " +
                    Path("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(ReadFileText(Path("report.json")));
  EXPECT_EQ(report["robustness"]["physics"], "on");
  const json& hold = report["nominal"]["hold"];
  EXPECT_LT(hold["end_tilt_deg"].get<double>(), 5.0);  // the example holds the pan level
  EXPECT_GT(hold["contacts"].get<int>(), 0);
  EXPECT_THAT(hold["load_bearers"].get<std::string>(), HasSubstr("thumb"));
  for (const json& t : report["trials"]) {
    const double mu = t["physics"]["hand_friction"];
    EXPECT_GE(mu, 0.75);
    EXPECT_LE(mu, 1.25);
    EXPECT_TRUE(t["hold"]["slip_m"].is_number());
  }
  const json& sensitivity = report["sensitivity"];
  EXPECT_EQ(sensitivity["trials_per_end"], 1);
  ASSERT_EQ(sensitivity["factors"].size(), 8u);
  EXPECT_EQ(sensitivity["factors"][0]["factor"], "hand_friction");
  EXPECT_EQ(sensitivity["factors"][0]["low"]["physics"]["hand_friction"], 0.75);
  EXPECT_EQ(sensitivity["factors"][7]["high"]["physics"]["time_step_s"], 0.001);
  EXPECT_THAT(r.err, HasSubstr("sensitivity (1 replays per end"));

  // and --physics off leaves every replay's physics as modelled.
  ASSERT_EQ(RunGraspsynth("simulate " + Example() + " --perturb 1 --physics off --out " +
                          Path("off.json"))
                .exit_code,
            0);
  const json off = json::parse(ReadFileText(Path("off.json")));
  EXPECT_EQ(off["trials"][0]["physics"]["hand_friction"], 1.0);
  EXPECT_EQ(off["trials"][0]["physics"]["time_step_s"], 0.004);
  EXPECT_NE(
      RunGraspsynth("simulate " + Example() + " --physics maybe --out " + Path("x.json")).exit_code,
      0);
}

// The nominal trial's hold margin reaches the report with the thresholds and their reasons; a
// required margin that the hold misses makes the command exit 1, with the report written.
TEST_F(SimulateCommand, ReportsTheHoldMarginAndExitsOneWhenARequiredOneIsMissed) {
  const auto r = RunGraspsynth("simulate " + Example() + " --out " + Path("margin.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json margin = json::parse(ReadFileText(Path("margin.json")))["nominal"]["hold_margin"];
  EXPECT_TRUE(margin["measured"].get<bool>());
  EXPECT_TRUE(margin["slip_mm"].is_number());
  EXPECT_TRUE(margin["epsilon_weight"].is_number());
  EXPECT_TRUE(margin["contacts"]["thumb"].is_number());
  EXPECT_EQ(margin["required"], false);
  EXPECT_EQ(margin["thresholds"]["max_slip_mm"], 40.0);
  EXPECT_THAT(margin["reasons"]["max_slip_mm"].get<std::string>(), HasSubstr("slides"));
  EXPECT_THAT(r.err, HasSubstr("hold margin: slip "));

  const auto required = RunGraspsynth("simulate " + Example() +
                                      " --require-hold-margin --min-epsilon-weight 1000 --out " +
                                      Path("required.json"));
  EXPECT_EQ(required.exit_code, 1) << required.err;
  const json report = json::parse(ReadFileText(Path("required.json")));
  EXPECT_EQ(report["nominal"]["success"], true);
  EXPECT_THAT(report["nominal"]["hold_margin"]["shortfall"].get<std::string>(),
              HasSubstr("< 1000 weights"));
}

TEST_F(SimulateCommand, SimulatesTheExampleAndWritesReportAndRecord) {
  const auto r = RunGraspsynth("simulate " + Example() + " --perturb 3 --threads 2 --out " +
                               Path("report.json") + " --record " + Path("states.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(ReadFileText(Path("report.json")));
  EXPECT_EQ(report["format"], "graspsynth-simulation/1");
  EXPECT_EQ(report["theta_deg"], 60.0);
  EXPECT_EQ(report["nominal"]["success"], true);
  EXPECT_EQ(report["nominal"]["outcome"], "success");
  EXPECT_GE(report["nominal"]["lift_m"].get<double>(), 0.05);
  EXPECT_FALSE(report["nominal"]["reason"].get<std::string>().empty());
  const json& rob = report["robustness"];
  EXPECT_EQ(rob["trials"], 3);
  const int k = rob["successes"];
  EXPECT_DOUBLE_EQ(rob["score"].get<double>(), k / 3.0 + 0.0 * k);
  ASSERT_EQ(rob["ci95"].size(), 2u);
  EXPECT_LE(rob["ci95"][0].get<double>(), rob["score"].get<double>());
  EXPECT_GE(rob["ci95"][1].get<double>(), rob["score"].get<double>() - 1e-9);
  ASSERT_EQ(report["trials"].size(), 3u);
  for (int i = 0; i < 3; ++i) {
    const json& t = report["trials"][i];
    EXPECT_EQ(t["index"], i);
    EXPECT_GE(t["time_scale"].get<double>(), 0.7);
    EXPECT_LE(t["time_scale"].get<double>(), 1.3);
    EXPECT_TRUE(t["success"].is_boolean());
    EXPECT_TRUE(t["reason"].is_string());
  }
  EXPECT_THAT(r.err, HasSubstr("nominal trial: success"));
  EXPECT_THAT(r.err, HasSubstr("simulating: 3/3"));
  // the record: a header and one row per 10 ms of the 6.3 s trial.
  std::istringstream csv(ReadFileText(Path("states.csv")));
  std::string header, line;
  std::getline(csv, header);
  EXPECT_THAT(header, HasSubstr("t,q1,q2"));
  EXPECT_THAT(header, HasSubstr(",f15,object_x"));
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_NEAR(rows, 631, 2);
}

// `graspsynth simulate FILE` as the README writes it: without --out the report's essentials go
// to stdout and no file is written; a grasp file is played as its "trajectory".
TEST_F(SimulateCommand, WithoutOutPrintsTheResultAndWritesNoFile) {
  const fs::path before = fs::current_path();
  fs::current_path(dir_);
  const auto r = RunGraspsynth("simulate " + Example() + " --perturb 2 --threads 2");
  fs::current_path(before);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr(Example() + ": nominal trial succeeded (success): lifted"));
  EXPECT_THAT(r.out, HasSubstr("  lift "));
  EXPECT_THAT(r.out, HasSubstr("robustness: "));
  EXPECT_THAT(r.out, HasSubstr(" of 2 perturbed trials succeeded"));
  EXPECT_TRUE(fs::is_empty(dir_));  // no file written

  // a failed grasp: exit 1, FAILED with its outcome and reason.
  const std::string open = EditedExample("open.json", [](json& doc) {
    for (json& s : doc["samples"]) s["hand"] = doc["samples"][0]["hand"];
  });
  const auto f = RunGraspsynth("simulate " + open);
  EXPECT_EQ(f.exit_code, 1) << f.err;
  EXPECT_THAT(f.out, HasSubstr(open + ": nominal trial FAILED (not_lifted): object not lifted"));
  EXPECT_THAT(f.out, Not(HasSubstr("robustness")));

  // a grasp file (graspsynth-grasp/1): its "trajectory" is played, the same trial.
  json grasp = {{"format", "graspsynth-grasp/1"},
                {"trajectory", json::parse(ReadFileText(Example()))}};
  std::ofstream(Path("grasp.json")) << grasp.dump();
  ASSERT_EQ(RunGraspsynth("simulate " + Path("grasp.json") + " --out " + Path("g.json")).exit_code,
            0);
  ASSERT_EQ(RunGraspsynth("simulate " + Example() + " --out " + Path("e.json")).exit_code, 0);
  json g = json::parse(ReadFileText(Path("g.json")));
  json e = json::parse(ReadFileText(Path("e.json")));
  EXPECT_EQ(g["nominal"]["lift_m"], e["nominal"]["lift_m"]);
  EXPECT_EQ(g["nominal"]["reason"], e["nominal"]["reason"]);
}

// --trial-record writes the nominal trial as simulated (graspsynth-trial-record/1): frames at
// --record-interval with the object's pose from the physics, contacts, the outcome; and the
// report of --out is the one without it.
TEST_F(SimulateCommand, TrialRecordHoldsTheTrialAsSimulated) {
  const auto r = RunGraspsynth("simulate " + Example() + " --record-interval 0.02 --trial-record " +
                               Path("trial.json") + " --out " + Path("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_EQ(RunGraspsynth("simulate " + Example() + " --out " + Path("plain.json")).exit_code, 0);
  EXPECT_EQ(ReadFileText(Path("report.json")), ReadFileText(Path("plain.json")));
  const json report = json::parse(ReadFileText(Path("report.json")));
  const json record = json::parse(ReadFileText(Path("trial.json")));
  EXPECT_EQ(record["format"], "graspsynth-trial-record/1");
  EXPECT_EQ(record["trajectory"], Example());
  EXPECT_EQ(record["theta_deg"], 60.0);
  EXPECT_EQ(record["record_interval_s"], 0.02);
  EXPECT_EQ(record["outcome"], "success");
  EXPECT_EQ(record["reason"], report["nominal"]["reason"]);
  const json& frames = record["frames"];
  ASSERT_GT(frames.size(), 100u);
  EXPECT_NEAR(frames[1]["t"].get<double>() - frames[0]["t"].get<double>(), 0.02, 1e-6);
  const double rest = frames[0]["object_position"][2];
  const double end = frames.back()["object_position"][2];
  EXPECT_NEAR(end - rest, report["nominal"]["lift_m"].get<double>(), 2e-3);
  EXPECT_GT(end - rest, 0.05);
  EXPECT_FALSE(frames.back()["contacts"].empty());  // the hand holds it at the end
  EXPECT_GT(frames.back()["contacts"][0]["f"].get<double>(), 0.0);

  // a record that cannot be written (its folder is a file) is a clear error.
  const auto bad =
      RunGraspsynth("simulate " + Example() + " --trial-record " + Path("report.json/trial.json"));
  EXPECT_EQ(bad.exit_code, 2) << bad.err;
  EXPECT_THAT(bad.err, HasSubstr("report.json"));
}

TEST_F(SimulateCommand, TheSameSeedGivesTheSameBytesWhateverTheThreads) {
  for (const char* threads : {"1", "2"}) {
    const auto r = RunGraspsynth("simulate " + Example() + " --perturb 4 --seed 9 --threads " +
                                 threads + " --out " + Path(std::string(threads) + ".json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(ReadFileText(Path("1.json")), ReadFileText(Path("2.json")));
}

TEST_F(SimulateCommand, AFailedGraspIsReportedWithItsReason) {
  const std::string open = EditedExample("open.json", [](json& doc) {
    for (json& s : doc["samples"]) s["hand"] = doc["samples"][0]["hand"];
  });
  const auto r = RunGraspsynth("simulate " + open + " --out " + Path("report.json"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json report = json::parse(ReadFileText(Path("report.json")));
  EXPECT_EQ(report["nominal"]["success"], false);
  EXPECT_EQ(report["nominal"]["outcome"], "not_lifted");
  EXPECT_THAT(report["nominal"]["reason"].get<std::string>(), HasSubstr("not lifted"));
  EXPECT_EQ(report["robustness"]["trials"], 0);
  EXPECT_TRUE(report["trials"].empty());
}

TEST_F(SimulateCommand, ABadPhysicsFlagIsNamedBeforeAnyTrialRuns) {
  for (const auto& [flags, named] : std::vector<std::pair<std::string, std::string>>{
           {"--friction-spread 1.5", "--friction-spread: "},
           {"--stiffness-range 2 1", "--stiffness-range: "},
           {"--fine-step-probability 2", "--fine-step-probability: "},
           {"--max-slip-mm 0", "--max-slip-mm: "},
           {"--min-load-bearing-links -2", "--min-load-bearing-links: "}}) {
    const auto r =
        RunGraspsynth("simulate " + Example() + " " + flags + " --out " + Path("bad.json"));
    EXPECT_EQ(r.exit_code, 2) << flags;
    EXPECT_THAT(r.err, HasSubstr(named));
    EXPECT_THAT(r.err, Not(HasSubstr("nominal trial")));  // nothing simulated first
    EXPECT_FALSE(fs::exists(Path("bad.json")));
  }
}

TEST_F(SimulateCommand, RejectsMalformedTrajectoriesNamingFileSampleAndField) {
  struct Case {
    std::string name;
    std::function<void(json&)> edit;
    std::vector<std::string> expected;
  };
  const std::vector<Case> cases = {
      {"format.json",
       [](json& d) { d["format"] = "graspsynth-demo/1"; },
       {"format.json",
        "field 'format': expected \"graspsynth-trajectory/1\", found \"graspsynth-demo/1\""}},
      {"joints.json",
       [](json& d) { d["samples"][5]["arm"].erase(2); },
       {"joints.json", "field 'samples[5].arm': expected an array of 7 finite numbers"}},
      {"time.json",
       [](json& d) { d["samples"][7]["t"] = 0.1; },
       {"time.json", "field 'samples[7].t': expected a time after the previous sample's",
        "found 0.1"}},
      {"limits.json",
       [](json& d) { d["samples"][3]["hand"][2] = 3.0; },
       {"limits.json", "field 'samples[3].hand[2]': expected a value within thumb_j3's limits",
        "found 3"}},
  };
  for (const Case& c : cases) {
    const auto r = RunGraspsynth("simulate " + EditedExample(c.name, c.edit) + " --out " +
                                 Path("report.json"));
    EXPECT_EQ(r.exit_code, 2) << c.name;
    for (const std::string& part : c.expected) EXPECT_THAT(r.err, HasSubstr(part)) << c.name;
    EXPECT_FALSE(fs::exists(Path("report.json"))) << c.name;
  }
  // a NaN as Python's json module writes it, in place of the first arm value of sample 10.
  std::string text = ReadFileText(Example());
  const std::string key = "\"arm\":[";
  const size_t first = text.find(key, text.find("\"t\":0.2,")) + key.size();
  const size_t comma = text.find(',', first);
  ASSERT_NE(comma, std::string::npos);
  text = text.substr(0, first) + "NaN" + text.substr(comma);
  std::ofstream(Path("nan.json")) << text;
  const auto r = RunGraspsynth("simulate " + Path("nan.json") + " --out " + Path("report.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(
      r.err,
      HasSubstr("nan.json: field 'samples[10].arm[0]': expected a finite number, found NaN"));
}

// --object names the object by its shipped name or by its file; the pan either way gives the
// report of the scene's own pan, and an unknown object or a broken object file is a clear error
// before any trial runs.
TEST_F(SimulateCommand, ObjectFlagTakesAShippedNameOrAFile) {
  ASSERT_EQ(RunGraspsynth("simulate " + Example() + " --out " + Path("scene.json")).exit_code, 0);
  const std::string pan_file = std::string(::testing::SourceDir()) + "/models/objects/pan.json";
  for (const std::string& object : {std::string("pan"), pan_file}) {
    const auto r =
        RunGraspsynth("simulate " + Example() + " --object " + object + " --out " + Path("o.json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(ReadFileText(Path("o.json")), ReadFileText(Path("scene.json"))) << object;
  }
  auto r = RunGraspsynth("simulate " + Example() + " --object teapot --out " + Path("t.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("unknown object 'teapot': not a file, and not a shipped object ("));
  EXPECT_THAT(r.err, HasSubstr("pan"));
  std::ofstream(Path("heavy.json"))
      << R"({"format": "graspsynth-object/1", "name": "heavy", "parts": [)"
      << R"({"name": "b", "type": "box", "size": [0.1, 0.1, 0.1], "mass": -1}]})";
  r = RunGraspsynth("simulate " + Example() + " --object " + Path("heavy.json") + " --out " +
                    Path("h.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr(Path("heavy.json") + ": field 'parts[0].mass': expected a number"));
  EXPECT_FALSE(fs::exists(Path("h.json")));
}

// The pan built from meshes (ODE trimeshes) lifts as the pan does, and its perturbed replays give
// the same report on one thread and on two: trimesh collisions are serialized (Debian's ODE shares
// one trimesh collider cache between threads; without the lock two threads crashed).
TEST_F(SimulateCommand, MeshObjectReplaysAreTheSameOnOneAndTwoThreads) {
  for (const char* threads : {"1", "2"}) {
    const auto r =
        RunGraspsynth("simulate " + Example() + " --object pan_mesh --perturb 6 --threads " +
                      threads + " --out " + Path(std::string("mesh") + threads + ".json"));
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  const std::string one = ReadFileText(Path("mesh1.json"));
  EXPECT_EQ(one, ReadFileText(Path("mesh2.json")));
  const json report = json::parse(one);
  EXPECT_EQ(report["nominal"]["outcome"], "success");
}

TEST_F(SimulateCommand, AConfigFileSetsTheOptionsAndTheFlagsOverrideIt) {
  std::ofstream(Path("options.json")) << R"({"perturb": 2, "seed": 5, "physics": false})";
  const auto r = RunGraspsynth("simulate " + Example() + " --config " + Path("options.json") +
                               " --perturb 1 --out " + Path("report.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(ReadFileText(Path("report.json")));
  EXPECT_EQ(report["robustness"]["trials"], 1);
  EXPECT_EQ(report["robustness"]["seed"], 5);
  EXPECT_EQ(report["robustness"]["physics"], "off");
  std::ofstream(Path("bad.json")) << R"({"perturb": -1})";
  const auto bad = RunGraspsynth("simulate " + Example() + " --config " + Path("bad.json") +
                                 " --out " + Path("x.json"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, HasSubstr("field 'perturb'"));
  EXPECT_FALSE(fs::exists(Path("x.json")));
}

TEST_F(SimulateCommand, HelpNamesEveryOption) {
  const auto r = RunGraspsynth("simulate --help");
  EXPECT_EQ(r.exit_code, 0);
  for (const char* option :
       {"--perturb", "--seed", "--threads", "--record", "--trial-record", "--out", "--fidelity",
        "--position-noise", "--object", "graspsynth-simulation/1"}) {
    EXPECT_THAT(r.out, HasSubstr(option));
  }
}

TEST_F(SimulateCommand, ScriptedGraspWritesTheExample) {
  const auto r = RunGraspsynth("scripted-grasp --theta 60 --out " + Path("g.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json made = json::parse(ReadFileText(Path("g.json")));
  const json shipped = json::parse(ReadFileText(Example()));
  ASSERT_EQ(made["samples"].size(), shipped["samples"].size());
  for (size_t i = 0; i < made["samples"].size(); i += 17) {
    for (int j = 0; j < 7; ++j) {
      EXPECT_NEAR(made["samples"][i]["arm"][j].get<double>(),
                  shipped["samples"][i]["arm"][j].get<double>(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace graspsynth
