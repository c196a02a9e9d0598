#include "motion/joint_trajectory.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}

// A small valid document: three samples, one waypoint.
json ValidDocument() {
  json samples = json::array();
  for (int i = 0; i < 3; ++i) {
    json arm = json::array(), hand = json::array();
    for (int j = 0; j < kArmDof; ++j) arm.push_back(0.1 * i + 0.01 * j);
    for (int k = 0; k < kHandDof; ++k) hand.push_back(k == 0 ? 0.5 : 0.02 * i);
    samples.push_back({{"t", 0.5 * i}, {"arm", arm}, {"hand", hand}});
  }
  return {{"format", "graspsynth-trajectory/1"},
          {"theta_deg", 60.0},
          {"comment", "test"},
          {"samples", samples},
          {"waypoints",
           {{{"t", 0.5}, {"position", {0.1, 0.2, 0.3}}, {"quaternion", {1.0, 0.0, 0.0, 0.0}}}}}};
}

JointTrajectory Parse(const json& doc) { return ParseJointTrajectory(doc.dump(), "traj.json"); }

TEST(JointTrajectory, ParsesAValidDocument) {
  const JointTrajectory t = Parse(ValidDocument());
  EXPECT_EQ(t.theta_deg, 60.0);
  ASSERT_EQ(t.samples.size(), 3u);
  EXPECT_EQ(t.samples[2].t, 1.0);
  EXPECT_DOUBLE_EQ(t.samples[1].arm[3], 0.13);
  EXPECT_DOUBLE_EQ(t.samples[2].hand[5], 0.04);
  ASSERT_EQ(t.waypoints.size(), 1u);
  EXPECT_TRUE(testing::MatricesNear(t.waypoints[0].p_WH, Eigen::Vector3d(0.1, 0.2, 0.3), 0.0));
  EXPECT_DOUBLE_EQ(t.duration(), 1.0);
  EXPECT_NO_THROW(CheckJointLimits(t, Robot().arm, Robot().hand, "traj.json"));
}

TEST(JointTrajectory, SampleAtInterpolatesAndClamps) {
  const JointTrajectory t = Parse(ValidDocument());
  const TrajectorySample mid = SampleAt(t, 0.75);
  EXPECT_NEAR(mid.arm[0], 0.15, 1e-15);
  EXPECT_NEAR(mid.hand[1], 0.03, 1e-15);
  EXPECT_EQ(SampleAt(t, -1.0).arm, t.samples.front().arm);
  EXPECT_EQ(SampleAt(t, 5.0).arm, t.samples.back().arm);
  EXPECT_EQ(SampleAt(t, 0.5).arm, t.samples[1].arm);
  const JointTrajectory slow = TimeScaled(t, 1.25);
  EXPECT_DOUBLE_EQ(slow.duration(), 1.25);
  EXPECT_DOUBLE_EQ(slow.waypoints[0].t, 0.625);
}

TEST(JointTrajectory, WritesAndReadsBack) {
  const JointTrajectory t = Parse(ValidDocument());
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "graspsynth_joint_trajectory_test.json";
  WriteJointTrajectory(path, t);
  const JointTrajectory back = LoadJointTrajectory(path, Robot().arm, Robot().hand);
  std::filesystem::remove(path);
  ASSERT_EQ(back.samples.size(), t.samples.size());
  for (size_t i = 0; i < t.samples.size(); ++i) {
    EXPECT_NEAR(back.samples[i].t, t.samples[i].t, 1e-10);
    EXPECT_TRUE(testing::MatricesNear(back.samples[i].arm, t.samples[i].arm, 1e-10));
    EXPECT_TRUE(testing::MatricesNear(back.samples[i].hand, t.samples[i].hand, 1e-10));
  }
  ASSERT_EQ(back.waypoints.size(), 1u);
  EXPECT_NEAR(back.waypoints[0].q_WH.w(), 1.0, 1e-12);
}

// Every malformed file is rejected with a message that names the file, the sample and the
// field.
TEST(JointTrajectory, RejectsMalformedDocumentsNamingFileSampleAndField) {
  json doc = ValidDocument();
  doc["format"] = "graspsynth-trajectory/2";
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'format': expected \"graspsynth-trajectory/1\", found "
                       "\"graspsynth-trajectory/2\"");

  doc = ValidDocument();
  doc["samples"][1]["arm"].erase(6);
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'samples[1].arm': expected an array of 7 finite numbers, "
                       "found [");

  doc = ValidDocument();
  doc["samples"][2]["hand"].push_back(0.0);
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "field 'samples[2].hand': expected an array of 16 finite numbers");

  doc = ValidDocument();
  doc["samples"][2]["t"] = 0.5;
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'samples[2].t': expected a time after the previous "
                       "sample's ",
                       "found 0.5");

  doc = ValidDocument();
  doc["samples"][1]["hand"][3] = "x";
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'samples[1].hand[3]': expected a finite number, found "
                       "\"x\"");

  doc = ValidDocument();
  doc["samples"][0].erase("hand");
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'samples[0].hand': expected an array of 16 finite "
                       "numbers, found nothing");

  doc = ValidDocument();
  doc["samples"] = json::array();
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'samples': expected a non-empty array of samples, found "
                       "[]");

  doc = ValidDocument();
  doc["waypoints"][0]["quaternion"] = {1.0, 1.0, 0.0, 0.0};
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "traj.json: field 'waypoints[0].quaternion': expected a unit quaternion",
                       "found [1.0,1.0,0.0,0.0]");

  GS_EXPECT_THROW_WITH(ParseJointTrajectory("{\"format\": ", "traj.json"), InputError,
                       "traj.json: not valid JSON");
}

TEST(JointTrajectory, NamesNonFiniteValuesWhereverTheyAre) {
  // JSON has no NaN; writers put it as a bare token (Python's json module) or as null.
  std::string text = ValidDocument().dump();
  const std::string needle = "\"arm\":[0.1,";
  const size_t at = text.find(needle);
  ASSERT_NE(at, std::string::npos);
  std::string bare = text;
  bare.replace(at, needle.size(), "\"arm\":[NaN,");
  GS_EXPECT_THROW_WITH(ParseJointTrajectory(bare, "traj.json"), InputError,
                       "traj.json: field 'samples[1].arm[0]': expected a finite number, found "
                       "NaN");
  std::string infinite = text;
  infinite.replace(at, needle.size(), "\"arm\":[-Infinity,");
  GS_EXPECT_THROW_WITH(ParseJointTrajectory(infinite, "traj.json"), InputError,
                       "field 'samples[1].arm[0]': expected a finite number, found -Infinity");
  json doc = ValidDocument();
  doc["samples"][2]["t"] = nullptr;
  GS_EXPECT_THROW_WITH(Parse(doc), InputError,
                       "field 'samples[2].t': expected a finite number, found null");
  // a NaN inside a string is text, not a number token.
  doc = ValidDocument();
  doc["comment"] = "NaN, Infinity";
  EXPECT_NO_THROW(Parse(doc));
}

TEST(JointTrajectory, RejectsJointValuesOutsideTheLimits) {
  json doc = ValidDocument();
  doc["samples"][1]["arm"][3] = 2.5;  // E1: +-137 deg = +-2.39 rad
  GS_EXPECT_THROW_WITH(CheckJointLimits(Parse(doc), Robot().arm, Robot().hand, "traj.json"),
                       InputError,
                       "traj.json: field 'samples[1].arm[3]': expected a value within E1's "
                       "limits [",
                       "] rad, found 2.5");
  doc = ValidDocument();
  doc["samples"][2]["hand"][6] = -0.1;  // index PIP: 0..90 deg
  GS_EXPECT_THROW_WITH(CheckJointLimits(Parse(doc), Robot().arm, Robot().hand, "traj.json"),
                       InputError,
                       "field 'samples[2].hand[6]': expected a value within index_j3's limits "
                       "[0, 1.570796327] rad, found -0.1");
  // E2 may go beyond +-180 deg (+-255 deg).
  doc = ValidDocument();
  doc["samples"][0]["arm"][4] = 4.0;
  EXPECT_NO_THROW(CheckJointLimits(Parse(doc), Robot().arm, Robot().hand, "traj.json"));
}

TEST(JointTrajectory, LoadNamesAMissingFile) {
  GS_EXPECT_THROW_WITH(LoadJointTrajectory("/nonexistent/t.json", Robot().arm, Robot().hand),
                       InputError, "cannot read trajectory file '/nonexistent/t.json'");
}

}  // namespace
}  // namespace graspsynth
