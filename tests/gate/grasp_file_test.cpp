#include "gate/grasp_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "tests/solver/synthesis_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using testing::Model406080;
using testing::ShippedSimulationModel;

namespace fs = std::filesystem;

fs::path TempDir() {
  const fs::path dir =
      fs::temp_directory_path() / ("graspsynth_grasp_file_" + std::to_string(::getpid()) + "_" +
                                   ::testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::create_directories(dir);
  return dir;
}

const SynthesisResult& Synthesized() {
  static const SynthesisResult r = [] {
    SynthesisData data(Model406080());
    return SynthesizeGrasp(Model406080(), 50.0, {}, &data);
  }();
  return r;
}

TEST(GraspFile, HoldsEverySectionAndAPlayableTrajectory) {
  ASSERT_TRUE(Synthesized().ok()) << Synthesized().message;
  PhysicsGateOptions go;
  go.robustness.trials = 0;
  const PhysicsGateResult gate =
      RunPhysicsGate(ShippedSimulationModel(), Synthesized().trajectory, go);
  const nlohmann::json j = nlohmann::json::parse(GraspFileToJson(Synthesized(), &gate, false));
  EXPECT_EQ(j["format"], "graspsynth-grasp/1");
  EXPECT_EQ(j["theta_deg"], 50.0);
  EXPECT_EQ(j["method"]["used"], "interp");
  EXPECT_EQ(j["sources"].size(), 2u);
  EXPECT_DOUBLE_EQ(
      j["sources"][0]["weight"].get<double>() + j["sources"][1]["weight"].get<double>(), 1.0);
  EXPECT_EQ(j["waypoints"].size(), Synthesized().motion.waypoints.size());
  EXPECT_EQ(j["waypoints"][0]["fingers"].size(), 16u);
  EXPECT_TRUE(j["refinement"]["refined"].get<bool>());
  EXPECT_TRUE(j["refinement"]["after"].contains("approach_clearance_m"));
  EXPECT_TRUE(j["refinement"]["ceres"].contains("termination"));
  EXPECT_TRUE(j["validation"]["passed"].is_boolean());
  EXPECT_TRUE(j["validation"]["robustness"].is_null());
  EXPECT_TRUE(j["quality"].contains("epsilon"));
  // the hold margin, its misses and the thresholds with their reasons.
  const nlohmann::json& margin = j["validation"]["hold_margin"];
  EXPECT_EQ(margin["slip_mm"].get<double>(), gate.hold_margin.slip_mm);
  EXPECT_EQ(margin["epsilon_weight"].get<double>(), gate.hold_margin.epsilon_weight);
  EXPECT_EQ(margin["load_bearing_links"].get<int>(), gate.hold_margin.load_bearing_links);
  EXPECT_EQ(margin["shortfall"], gate.hold_margin_shortfall);
  EXPECT_EQ(margin["required"], false);
  EXPECT_EQ(margin["thresholds"].size(), margin["reasons"].size());
  EXPECT_EQ(margin["thresholds"]["min_load_bearing_links"], 2.0);
  // the trajectory member is a graspsynth-trajectory/1 document.
  const JointTrajectory t = ParseJointTrajectory(j["trajectory"].dump(), "test");
  EXPECT_EQ(t.samples.size(), Synthesized().trajectory.samples.size());
}

TEST(GraspFile, SimulateReadsAGraspFileOrATrajectoryFile) {
  ASSERT_TRUE(Synthesized().ok());
  const fs::path dir = TempDir();
  WriteGraspFile(dir / "grasp.json", Synthesized(), nullptr, false);
  WriteJointTrajectory(dir / "traj.json", Synthesized().trajectory);
  const RobotModel& robot = ShippedSimulationModel().robot();
  const JointTrajectory a = LoadTrajectoryOrGraspFile(dir / "grasp.json", robot.arm, robot.hand);
  const JointTrajectory b = LoadTrajectoryOrGraspFile(dir / "traj.json", robot.arm, robot.hand);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  EXPECT_TRUE(a.samples.back().arm.isApprox(b.samples.back().arm, 1e-9));
  std::ofstream(dir / "empty.json") << R"({"format": "graspsynth-grasp/1"})";
  try {
    LoadTrajectoryOrGraspFile(dir / "empty.json", robot.arm, robot.hand);
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "empty.json").string() +
                                         ": field 'trajectory': expected an object, found nothing");
  }
  // the trajectory member's fields are named by their path in the grasp file.
  std::ofstream(dir / "bad.json")
      << R"({"format": "graspsynth-grasp/1", "trajectory": {"format": "graspsynth-trajectory/1",
            "theta_deg": 60, "samples": [{"t": 0, "arm": [0, 0, 0, 0, 0, 0, 0], "hand": []}]}})";
  GS_EXPECT_THROW_WITH(LoadTrajectoryOrGraspFile(dir / "bad.json", robot.arm, robot.hand),
                       InputError,
                       (dir / "bad.json").string() +
                           ": field 'trajectory.samples[0].hand': expected an array of 16 finite "
                           "numbers, found []");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace graspsynth
