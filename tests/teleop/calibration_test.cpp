#include "teleop/calibration.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::teleop {
namespace {

std::string ErrorOf(const std::string& text) {
  try {
    ParseTeleopCalibration(text, "calib.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TeleopCalibration, TheShippedFileLoadsAndTheInverseRoundTrips) {
  const TeleopCalibration c = LoadTeleopCalibration(DefaultTeleopCalibrationPath());
  EXPECT_FALSE(c.X_WT.isApprox(Eigen::Isometry3d::Identity()));
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).matrix();
  X_WH.translation() = Eigen::Vector3d(-0.2, 0.6, 0.3);
  const Eigen::Isometry3d back = c.WristInWorld(c.SensorInTracker(X_WH));
  EXPECT_TRUE(testing::MatricesNear(back.matrix(), X_WH.matrix(), 1e-12));
}

TEST(TeleopCalibration, ComposesTrackerReadingAndWristOffset) {
  const TeleopCalibration c = ParseTeleopCalibration(
      R"({"format": "graspsynth-teleop-config/1",
          "tracker_in_world": {"position": [1, 2, 3], "quaternion": [0, 0, 0, 1]},
          "sensor_to_wrist": {"position": [0, 0, 0.1], "quaternion": [1, 0, 0, 0]}})",
      "inline");
  // a half turn about z: tracker x is world -x; the wrist sits 0.1 m along the sensor's z.
  const Eigen::Isometry3d X_WH =
      c.WristInWorld(Eigen::Isometry3d(Eigen::Translation3d(0.5, 0.0, 0.0)));
  EXPECT_TRUE(testing::MatricesNear(X_WH.translation(), Eigen::Vector3d(0.5, 2, 3.1), 1e-12));
  // sensor_to_wrist may be left out.
  const TeleopCalibration d = ParseTeleopCalibration(
      R"({"format": "graspsynth-teleop-config/1",
          "tracker_in_world": {"position": [0, 0, 0], "quaternion": [1, 0, 0, 0]}})",
      "inline");
  EXPECT_TRUE(d.X_SH.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(TeleopCalibration, BadFilesNameTheFieldAndTheValue) {
  const std::string pose = R"({"position": [0, 0, 0], "quaternion": [1, 0, 0, 0]})";
  EXPECT_EQ(ErrorOf("{").rfind("calib.json: not valid JSON: parse error at line 1", 0), 0u);
  EXPECT_EQ(ErrorOf(R"({"format": "other/1", "tracker_in_world": )" + pose + "}"),
            "calib.json: field 'format': expected \"graspsynth-teleop-config/1\", found "
            "\"other/1\"");
  EXPECT_EQ(ErrorOf(R"({"format": "graspsynth-teleop-config/1"})"),
            "calib.json: field 'tracker_in_world': expected an object, found nothing");
  EXPECT_EQ(
      ErrorOf(R"({"format": "graspsynth-teleop-config/1", "tracker_in_wrold": )" + pose + "}"),
      "calib.json: field 'tracker_in_wrold': expected only the fields format, "
      "tracker_in_world, sensor_to_wrist here, found {\"position\":[0,0,0],\"quaternion\""
      ":[1,0,0,0]}");
  const std::string bad_q =
      R"({"format": "graspsynth-teleop-config/1", "tracker_in_world": {"position": [0, 0, 0],
          "quaternion": [1, 1, 0, 0]}})";
  EXPECT_EQ(ErrorOf(bad_q),
            "calib.json: field 'tracker_in_world.quaternion': expected a unit quaternion [w, x, "
            "y, z] (norm within 1e-06 of 1; norm 1.41421), found [1,1,0,0]");
  const std::string bad_p =
      R"({"format": "graspsynth-teleop-config/1", "tracker_in_world": {"position": [0, "a", 0],
          "quaternion": [1, 0, 0, 0]}})";
  EXPECT_EQ(ErrorOf(bad_p),
            "calib.json: field 'tracker_in_world.position[1]': expected a finite number, found "
            "\"a\"");
  EXPECT_THROW(LoadTeleopCalibration("/nonexistent/calib.json"), InputError);
}

}  // namespace
}  // namespace graspsynth::teleop
