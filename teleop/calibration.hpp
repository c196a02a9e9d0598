#pragma once

/// @file
/// The operator's calibration: where the motion tracker's frame T lies in the robot's world W,
/// and where the robot's wrist H lies relative to the tracker's sensor S on the operator's
/// wrist. An operator command carries X_TS (the sensor in the tracker frame); the robot's wrist
/// target is
///
///   X_WH = X_WT * X_TS * X_SH.
///
/// The file (JSON, `graspsynth-teleop-config/1`; examples/teleop_calibration.json is the
/// default):
///
///     {"format": "graspsynth-teleop-config/1",
///      "tracker_in_world": {"position": [x, y, z], "quaternion": [w, x, y, z]},   X_WT
///      "sensor_to_wrist":  {"position": [x, y, z], "quaternion": [w, x, y, z]}}   X_SH
///
/// Metres; quaternions unit within 1e-6 (normalized on reading). `sensor_to_wrist` may be left
/// out (identity). Unknown keys are refused, so a misspelt key is not silently ignored.

#include <filesystem>
#include <string>
#include <string_view>

#include "kinematics/types.hpp"

namespace graspsynth::teleop {

/// The `format` value of a calibration file.
inline constexpr std::string_view kTeleopConfigFormat = "graspsynth-teleop-config/1";

/// The two fixed transforms of the end-effector mapping (see the file comment).
struct TeleopCalibration {
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();  ///< tracker frame in world
  Eigen::Isometry3d X_SH = Eigen::Isometry3d::Identity();  ///< robot wrist in the sensor frame

  /// The robot's wrist target X_WH for a tracker reading X_TS.
  Eigen::Isometry3d WristInWorld(const Eigen::Isometry3d& X_TS) const { return X_WT * X_TS * X_SH; }
  /// The tracker reading X_TS that maps to the wrist pose X_WH (the inverse of WristInWorld;
  /// what a replaying client sends).
  Eigen::Isometry3d SensorInTracker(const Eigen::Isometry3d& X_WH) const {
    return X_WT.inverse() * X_WH * X_SH.inverse();
  }
};

/// Parses a calibration document. `source` names it in messages. Throws InputError naming the
/// source, the field and the value: not JSON, another format, a missing or unknown key, a
/// position that is not three finite numbers, a quaternion that is not four finite numbers of
/// norm 1 within 1e-6.
TeleopCalibration ParseTeleopCalibration(std::string_view json_text, const std::string& source);

/// Reads and parses the calibration file at `path`. Throws InputError when it cannot be read or
/// is malformed.
TeleopCalibration LoadTeleopCalibration(const std::filesystem::path& path);

/// examples/teleop_calibration.json below the data folder (common/data_dir.hpp).
std::filesystem::path DefaultTeleopCalibrationPath();

}  // namespace graspsynth::teleop
