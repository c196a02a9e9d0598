// Tests of `graspsynth export-mjcf` and `graspsynth simulate --engine mujoco` through the built
// binary.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "simulation_mujoco/mujoco_world.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RunGraspsynth;

std::string Example() { return std::string(::testing::SourceDir()) + "/examples/grasp_60deg.json"; }

class MujocoCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("graspsynth_mujoco_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
};

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(MujocoCommand, ExportedModelLoadsAndSteps) {
  const auto r = RunGraspsynth("export-mjcf --theta 45 --at -0.3,0.8 --out " + Path("pan.xml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string xml = ReadFileText(Path("pan.xml"));
  EXPECT_THAT(xml, HasSubstr("<mujoco model=\"graspsynth\">"));
  if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  const SimulationModel& model = testing::ShippedSimulationModel();
  const MujocoModel mujoco(model, MjcfModel{xml, {}});
  MujocoData data(mujoco, Vector7d::Zero(), HandVector::Zero());
  for (int n = 0; n < 200; ++n) data.Step();
  EXPECT_TRUE(data.IsFinite());
  // the object stands where --at and --theta put it, and stays there.
  const Eigen::Isometry3d X_WO =
      model.scene().ObjectPose(Placement{Radians(45.0), Eigen::Vector2d(-0.3, 0.8)});
  EXPECT_LT((data.object_pose().translation() - X_WO.translation()).norm(), 1e-3);
}

TEST_F(MujocoCommand, ATrajectoryBecomesKeyframes) {
  const auto r = RunGraspsynth("export-mjcf --trajectory " + Example() + " --mujoco-servo soft" +
                               " --out " + Path("grasp.xml"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json t = json::parse(ReadFileText(Example()));
  EXPECT_EQ(Count(ReadFileText(Path("grasp.xml")), "<key "), static_cast<int>(t["samples"].size()));
}

TEST_F(MujocoCommand, BadExportInputExitsTwo) {
  auto r = RunGraspsynth("export-mjcf --mujoco-servo hard --out " + Path("x.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--mujoco-servo"));
  r = RunGraspsynth("export-mjcf --time-step 0.5 --out " + Path("x.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--time-step"));
  r = RunGraspsynth("export-mjcf --at 9,9 --out " + Path("x.xml"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--at"));
  EXPECT_FALSE(fs::exists(Path("x.xml")));
}

TEST_F(MujocoCommand, UnknownEngineExitsTwo) {
  const auto r = RunGraspsynth("simulate " + Example() + " --engine foo");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--engine"));
  EXPECT_THAT(r.err, HasSubstr("foo"));
}

TEST_F(MujocoCommand, WhatOnlyOdeDoesIsRefusedUpFront) {
  const auto r = RunGraspsynth("simulate " + Example() + " --engine mujoco --perturb 2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--perturb"));
}

// the open hand does not lift the pan in MuJoCo either; the report says which engine ran.
TEST_F(MujocoCommand, OpenHandDoesNotLiftThePanInMujoco) {
  if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  ASSERT_EQ(
      RunGraspsynth("scripted-grasp --theta 60 --keep-open --out " + Path("open.json")).exit_code,
      0);
  const auto r = RunGraspsynth("simulate " + Path("open.json") + " --engine mujoco --out " +
                               Path("report.json"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const json report = json::parse(ReadFileText(Path("report.json")));
  EXPECT_EQ(report["settings"]["engine"], "mujoco");
  EXPECT_EQ(report["settings"]["mujoco_servo"], "stiff");
  EXPECT_EQ(report["nominal"]["outcome"], "not_lifted");
  EXPECT_LT(report["nominal"]["max_lift_m"].get<double>(), 0.01);
}

// ODE's report is as it was: no engine key.
TEST_F(MujocoCommand, OdeReportHasNoEngineKey) {
  const auto r = RunGraspsynth("simulate " + Example() + " --out " + Path("ode.json"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json report = json::parse(ReadFileText(Path("ode.json")));
  EXPECT_FALSE(report["settings"].contains("engine"));
  EXPECT_EQ(report["settings"]["fidelity"], "fast");
}

// --engines: a value that is not an engine list is bad input (exit 2, the flag named); MuJoCo
// asked for in a build without it is refused up front.
TEST_F(MujocoCommand, BadEnginesExitTwo) {
  auto r = RunGraspsynth("synthesize --theta 60 --engines ode,bullet --out " + Path("g.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--engines"));
  EXPECT_THAT(r.err, HasSubstr("ode,bullet"));
  r = RunGraspsynth("run --quick --engines mujoco --out " + Path("study"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--engines"));
  r = RunGraspsynth("synthesize --theta 60 --engines ode,mujoco --mujoco-min-success 2 --out " +
                    Path("g.json"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--mujoco-min-success"));
  EXPECT_FALSE(fs::exists(Path("g.json")));
  if (!MujocoAvailable()) {
    r = RunGraspsynth("synthesize --theta 60 --engines ode,mujoco --out " + Path("g.json"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_THAT(r.err, HasSubstr("built without MuJoCo"));
  }
}

TEST_F(MujocoCommand, TheSweepNeedsTheMujocoEngine) {
  const auto r = RunGraspsynth("simulate " + Example() + " --mujoco-sweep");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--mujoco-sweep needs --engine mujoco"));
}

// the sweep of the open hand's first half second (cheap: 16 short runs), none lifts the pan;
// one line per run and the report.
TEST_F(MujocoCommand, SweepOfTheOpenHand) {
  if (!MujocoAvailable()) GTEST_SKIP() << "built without MuJoCo";
  ASSERT_EQ(
      RunGraspsynth("scripted-grasp --theta 60 --keep-open --out " + Path("open.json")).exit_code,
      0);
  json open = json::parse(ReadFileText(Path("open.json")));
  json samples = json::array();
  for (const json& s : open["samples"]) {
    if (s["t"].get<double>() <= 0.5) samples.push_back(s);
  }
  open["samples"] = samples;
  open.erase("waypoints");
  std::ofstream(Path("short.json")) << open.dump();
  const auto r = RunGraspsynth("simulate " + Path("short.json") +
                               " --engine mujoco --mujoco-sweep --hold 0.1 --threads 2 --out " +
                               Path("sweep.json"));
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(Count(r.err, "not_lifted"), 16) << r.err;
  const json report = json::parse(ReadFileText(Path("sweep.json")));
  EXPECT_EQ(report["format"], "graspsynth-mujoco-sweep/1");
  EXPECT_EQ(report["summary"]["runs"], 16);
  EXPECT_EQ(report["summary"]["successes"], 0);
  ASSERT_EQ(report["runs"].size(), 16u);
  EXPECT_EQ(report["runs"][0]["setting"], "nominal");
  EXPECT_EQ(report["runs"][1]["servo"], "soft");
  EXPECT_EQ(report["runs"][15]["setting"], "friction_0.75");
}

}  // namespace
}  // namespace graspsynth
