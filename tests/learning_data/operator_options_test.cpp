// Tests of the synthetic operator's options file (graspsynth-operator/1).

#include "learning_data/operator_options.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <optional>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path TempFile(const std::string& name) {
  return fs::temp_directory_path() /
         ("graspsynth_operator_options_" + std::to_string(::getpid()) + "_" + name);
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
  a.plans.front().strategies.push_back({0.5, 0.3, -70.0, std::nullopt});
  GraspStyle own;
  own.hook_reach = 0.12;
  own.max_pitch = 0.5;
  own.yaw_offset = -0.2;
  own.roll = 0.1;
  own.closed_hand[2] = 0.7;
  a.plans.back().strategies.push_back({1.0, 0.33, -50.0, own});
  const fs::path path = TempFile("roundtrip.json");
  WriteOperatorOptions(a, path);
  const OperatorOptions b = ReadOperatorOptions(path);
  EXPECT_EQ(b.seed, 99u);
  EXPECT_NEAR(b.yaw_noise, 0.1, 1e-15);
  EXPECT_EQ(b.plans.size(), a.plans.size());
  EXPECT_EQ(b.plans.front().strategies.size(), a.plans.front().strategies.size());
  EXPECT_EQ(b.plans.front().strategies.back().eta_deg, -70.0);
  EXPECT_TRUE(testing::MatricesNear(b.grasp.closed_hand, a.grasp.closed_hand, 1e-12));
  EXPECT_FALSE(b.plans.front().strategies.back().grasp.has_value());
  // a strategy's own grip comes back whole.
  const std::optional<GraspStyle>& back = b.plans.back().strategies.back().grasp;
  ASSERT_TRUE(back.has_value());
  EXPECT_NEAR(back->hook_reach, 0.12, 1e-15);
  EXPECT_NEAR(back->max_pitch, 0.5, 1e-15);
  EXPECT_NEAR(back->yaw_offset, -0.2, 1e-15);
  EXPECT_NEAR(back->roll, 0.1, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(back->closed_hand, own.closed_hand, 1e-12));
  EXPECT_TRUE(testing::MatricesNear(back->open_hand, own.open_hand, 1e-12));
  fs::remove(path);
}

TEST(OperatorOptions, ThumbCloseDurationIsReadWrittenWhereUsedAndChecked) {
  OperatorOptions a = ReadOperatorOptions(DefaultOperatorOptionsPath());
  GraspStyle own = a.grasp;
  own.thumb_close_duration = 0.4;
  a.plans.front().strategies.front().grasp = own;
  const fs::path path = TempFile("thumb.json");
  WriteOperatorOptions(a, path);
  const OperatorOptions b = ReadOperatorOptions(path);
  ASSERT_TRUE(b.plans.front().strategies.front().grasp.has_value());
  EXPECT_EQ(b.plans.front().strategies.front().grasp->thumb_close_duration, 0.4);
  // the top level's 0 is the default and is not written: older files keep their bytes.
  EXPECT_EQ(b.grasp.thumb_close_duration, 0.0);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text.find("thumb_close_duration"), text.rfind("thumb_close_duration"));
  // a strategy's grip inherits the top level's.
  std::ofstream(path) << R"({"format": "graspsynth-operator/1", "thumb_close_duration": 0.3,
      "plans": [{"theta_deg": 20, "pregrasp_eta_deg": -70, "strategies": [{"weight": 1,
      "d": 0.3, "eta_deg": -70, "grasp": {"hook_reach": 0.1}}]}]})";
  const OperatorOptions c = ReadOperatorOptions(path);
  EXPECT_EQ(c.grasp.thumb_close_duration, 0.3);
  EXPECT_EQ(c.plans.front().strategies.front().grasp->thumb_close_duration, 0.3);
  std::ofstream(path) << R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20,
      "pregrasp_eta_deg": -70, "strategies": [{"weight": 1, "d": 0.3, "eta_deg": -70,
      "grasp": {"thumb_close_duration": -0.1}}]}]})";
  GS_EXPECT_THROW_WITH(ReadOperatorOptions(path), InputError, path.string(),
                       "thumb_close_duration must be finite and >= 0");
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
  expect_error(R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20,
      "pregrasp_eta_deg": -70, "strategies": [{"weight": 1, "d": 0.3, "eta_deg": -70,
      "grasp": {"roll_deg": "left"}}]}]})",
               "plans[0].strategies[0].grasp.roll_deg");
  expect_error(R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20,
      "pregrasp_eta_deg": -70, "strategies": [{"weight": 1, "d": 0.3, "eta_deg": -70,
      "grasp": {"max_pitch_deg": 95}}]}]})",
               "max_pitch_deg must be in [0, 90)");
  // a lift and hold shorter than two samples would put the grasp mark on the end sample.
  expect_error(R"({"format": "graspsynth-operator/1", "lift_duration": 1e-6,
      "hold_duration": 1e-6, "plans": [{"theta_deg": 20, "pregrasp_eta_deg": -70,
      "strategies": [{"weight": 1, "d": 0.3, "eta_deg": -70}]}]})",
               "lift_duration + hold_duration");
  GS_EXPECT_THROW_WITH(ReadOperatorOptions(TempFile("missing.json")), InputError,
                       "cannot read synthetic operator file", "missing.json': no such file");
  fs::remove(path);
}

TEST(OperatorOptions, ErrorsUseTheReadersWording) {
  const fs::path path = TempFile("wording.json");
  std::ofstream(path) << R"({"format": "graspsynth-operator/1", "plans": [{"theta_deg": 20,
      "pregrasp_eta_deg": -70, "strategies": [{"weight": 1, "d": 0.3, "eta_deg": -70,
      "grasp": {"closed_hand_deg": [1, 2]}}]}]})";
  GS_EXPECT_THROW_WITH(ReadOperatorOptions(path), InputError,
                       path.string() +
                           ": field 'plans[0].strategies[0].grasp.closed_hand_deg': expected an "
                           "array of 16 finite numbers, found [1,2]");
  std::ofstream(path) << R"({"format": "graspsynth-operator/1", "trials_per_orientation": 0,
      "plans": []})";
  GS_EXPECT_THROW_WITH(ReadOperatorOptions(path), InputError,
                       path.string() +
                           ": field 'trials_per_orientation': expected an integer in [1, "
                           "2147483647], found 0");
  fs::remove(path);
}

}  // namespace
}  // namespace graspsynth
