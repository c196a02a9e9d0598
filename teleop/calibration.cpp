#include "teleop/calibration.hpp"

#include <cmath>
#include <optional>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/json_reader.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth::teleop {
namespace {

Eigen::Isometry3d Pose(const JsonReader& object) {
  object.AsObject().RejectUnknownKeys({"position", "quaternion"});
  const Eigen::Vector3d p = object.Vector3("position");
  const Eigen::Quaterniond quaternion = object.UnitQuaternion("quaternion", 1e-6);
  Eigen::Isometry3d X = PoseFrom(p, quaternion.normalized());
  return X;
}

}  // namespace

TeleopCalibration ParseTeleopCalibration(std::string_view json_text, const std::string& source) {
  const JsonReader doc = JsonReader::Parse(json_text, source).AsObject();
  doc.RejectUnknownKeys({"format", "tracker_in_world", "sensor_to_wrist"});
  doc.ExpectString("format", kTeleopConfigFormat);
  TeleopCalibration calibration;
  calibration.X_WT = Pose(doc.Field("tracker_in_world"));
  if (const auto sensor_to_wrist = doc.OptionalField("sensor_to_wrist")) {
    calibration.X_SH = Pose(*sensor_to_wrist);
  }
  return calibration;
}

TeleopCalibration LoadTeleopCalibration(const std::filesystem::path& path) {
  return ParseTeleopCalibration(ReadInputFile(path, input_kind::kCalibration), path.string());
}

std::filesystem::path DefaultTeleopCalibrationPath() {
  return DataDirectory() / "examples" / "teleop_calibration.json";
}

}  // namespace graspsynth::teleop
