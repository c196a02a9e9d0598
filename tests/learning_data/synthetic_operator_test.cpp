// Tests of the synthetic operator: its options file, and trials that are made, executed in the
// simulation, labelled by what happened there, and reproducible whatever the thread count.

#include "learning_data/synthetic_operator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/errors.hpp"
#include "learning_data/segmentation.hpp"
#include "simulation/simulation_model.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TempFile(const std::string& name) {
  return fs::temp_directory_path() /
         ("graspsynth_operator_" + std::to_string(::getpid()) + "_" + name);
}

// One orientation of the shipped operator, with `trials` trials.
OperatorOptions OneOrientation(double theta_deg, int trials) {
  OperatorOptions options = ReadOperatorOptions(DefaultOperatorOptionsPath());
  std::vector<OrientationPlan> plans;
  for (const OrientationPlan& p : options.plans) {
    if (p.theta_deg == theta_deg) plans.push_back(p);
  }
  EXPECT_EQ(plans.size(), 1u);
  if (trials > 0) plans.front().trials = trials;
  options.plans = plans;
  return options;
}

TEST(OperatorOptions, ShippedFileIsValidAndCoversThePaperOrientations) {
  const OperatorOptions options = ReadOperatorOptions(DefaultOperatorOptionsPath());
  std::string why;
  EXPECT_TRUE(options.IsValid(&why)) << why;
  ASSERT_EQ(options.plans.size(), 9u);
  for (size_t i = 0; i < options.plans.size(); ++i) {
    EXPECT_EQ(options.plans[i].theta_deg, 20.0 + 10.0 * static_cast<double>(i));
  }
}

TEST(OperatorOptions, WriteThenReadGivesTheSameOptions) {
  OperatorOptions a = ReadOperatorOptions(DefaultOperatorOptionsPath());
  a.seed = 99;
  a.yaw_noise = 0.1;
  a.plans.front().strategies.push_back({0.5, 0.3, -70.0});
  const fs::path path = TempFile("roundtrip.json");
  WriteOperatorOptions(a, path);
  const OperatorOptions b = ReadOperatorOptions(path);
  EXPECT_EQ(b.seed, 99u);
  EXPECT_NEAR(b.yaw_noise, 0.1, 1e-15);
  EXPECT_EQ(b.plans.size(), a.plans.size());
  EXPECT_EQ(b.plans.front().strategies.size(), a.plans.front().strategies.size());
  EXPECT_EQ(b.plans.front().strategies.back().eta_deg, -70.0);
  EXPECT_TRUE(testing::MatricesNear(b.closed_hand, a.closed_hand, 1e-12));
  fs::remove(path);
}

TEST(OperatorOptions, BadFilesNameTheFileAndTheField) {
  const fs::path path = TempFile("bad.json");
  auto expect_error = [&](const std::string& text, const std::string& message) {
    std::ofstream(path) << text;
    GS_EXPECT_THROW_WITH(ReadOperatorOptions(path), InputError, message);
    try {
      ReadOperatorOptions(path);
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path.string()));
    }
  };
  expect_error("{", "not valid JSON");
  expect_error(R"({"format": "graspsynth-operator/2", "plans": []})", "field 'format'");
  expect_error(R"({"format": "graspsynth-operator/1"})", "field 'plans'");
  expect_error(R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20}]})",
               "plans[0].pregrasp_eta_deg");
  expect_error(R"({"format": "graspsynth-operator/1", "hook_reach": "far", "plans": []})",
               "field 'hook_reach'");
  expect_error(R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20,
      "pregrasp_eta_deg": -70, "strategies": [{"weight": 1, "d": -0.3, "eta_deg": -70}]}]})",
               "strategy d must be > 0");
  GS_EXPECT_THROW_WITH(ReadOperatorOptions(TempFile("missing.json")), InputError, "cannot open");
  fs::remove(path);
}

TEST(SyntheticOperator, TrialsAreCompleteLogsLabelledByTheSimulation) {
  const SimulationModel model = LoadDefaultSimulationModel();
  const OperatorOptions options = OneOrientation(100.0, 3);
  const std::vector<OperatorTrial> trials = GenerateDemonstrations(model, options, 1);
  ASSERT_EQ(trials.size(), 3u);
  SegmentationOptions segmentation;
  segmentation.region = model.scene().grasp_region;
  for (const OperatorTrial& t : trials) {
    SCOPED_TRACE(t.log.source);
    // the text is a valid v1 log that reads back to the same text.
    const std::string text = FormatDemoLog(t.log);
    EXPECT_EQ(FormatDemoLog(ParseDemoLog(text, t.log.source)), text);
    EXPECT_EQ(t.log.metadata.sample_rate_hz.value_or(0.0), 60.0);
    EXPECT_NEAR(t.log.samples[1].t - t.log.samples[0].t, 1.0 / 60.0, 1e-12);
    const SegmentedTrial s = Segment(t.log, segmentation);
    ASSERT_TRUE(s.ok()) << s.message;
    // entered from outside the region; the grasp comes before the end.
    EXPECT_GT(s.pregrasp, 0u);
    EXPECT_LT(s.grasp, s.end);
    // the label is the simulated object's: it moved only if the simulation moved it, and the
    // success flag agrees with the segmentation's reading of the object columns.
    EXPECT_EQ(t.success, s.success);
    EXPECT_EQ(t.success, t.outcome == "success") << t.reason;
    if (t.success) {
      EXPECT_GT(s.lift, 0.05);
    }
  }
}

TEST(SyntheticOperator, SameSeedSameLogsWhateverTheThreadCount) {
  const SimulationModel model = LoadDefaultSimulationModel();
  OperatorOptions options = OneOrientation(80.0, 2);
  const std::vector<OperatorTrial> one = GenerateDemonstrations(model, options, 1);
  const std::vector<OperatorTrial> two = GenerateDemonstrations(model, options, 2);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(FormatDemoLog(one[i].log), FormatDemoLog(two[i].log));
  }
  options.seed += 1;
  const std::vector<OperatorTrial> other = GenerateDemonstrations(model, options, 2);
  EXPECT_NE(FormatDemoLog(other[0].log), FormatDemoLog(one[0].log));
}

TEST(SyntheticOperator, TheShippedSetIsReproducedByteForByte) {
  // the shipped logs of one orientation come out of the shipped config again, bit for bit.
  const SimulationModel model = LoadDefaultSimulationModel();
  const OperatorOptions options = OneOrientation(100.0, 0);
  const std::vector<OperatorTrial> trials = GenerateDemonstrations(model, options, 2);
  ASSERT_FALSE(trials.empty());
  const fs::path shipped = DefaultOperatorOptionsPath().parent_path();
  for (const OperatorTrial& t : trials) {
    std::ifstream in(shipped / t.log.source, std::ios::binary);
    ASSERT_TRUE(in) << t.log.source;
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_EQ(FormatDemoLog(t.log), text) << t.log.source;
  }
}

TEST(SyntheticOperator, InvalidOptionsAreRejected) {
  const SimulationModel model = LoadDefaultSimulationModel();
  OperatorOptions options;
  GS_EXPECT_THROW_WITH(GenerateDemonstrations(model, options), InputError, "plan");
}

}  // namespace
}  // namespace graspsynth
