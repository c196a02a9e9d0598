#pragma once

/// @file
/// A joint-space trajectory of the whole robot (7 arm joints, 16 actuated hand joints) with
/// optional Cartesian wrist waypoints, and its file format `graspsynth-trajectory/1`:
///
///     {"format": "graspsynth-trajectory/1",
///      "theta_deg": 60.0,                                  object orientation, degrees
///      "object_xy": [x, y],             optional: the object centre on the table, world, m
///      "samples": [{"t": 0.0, "arm": [7 rad], "hand": [16 rad]}, ...],
///      "waypoints": [{"t": 1.5, "position": [x, y, z], "quaternion": [w, x, y, z]}, ...]}
///
/// `samples` are the commands of the robot's controller, strictly increasing in time and played
/// with linear interpolation between them; `hand` is in the order f0..f15 of models/README.md.
/// `waypoints` (optional) are poses X_WH of the hand-mount frame H ("wrist") in world at
/// chosen instants (metres, unit quaternion w first); they say where the trajectory's shape
/// comes from (e.g. pre-grasp and grasp poses) and are where robustness evaluation perturbs
/// it. Other top-level keys (a "comment", provenance) are kept out of the way and ignored.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/json_reader.hpp"
#include "kinematics/arm_model.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/types.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// The `format` value of a trajectory file.
inline constexpr std::string_view kJointTrajectoryFormat = "graspsynth-trajectory/1";

/// One command sample of the robot.
struct TrajectorySample {
  double t = 0.0;                        ///< s from the start of the trajectory
  Vector7d arm = Vector7d::Zero();       ///< arm joints S1..W2, rad
  HandVector hand = HandVector::Zero();  ///< actuated hand joints f0..f15, rad
};

/// A Cartesian wrist waypoint: the pose X_WH of the hand-mount frame H at time t.
struct WristWaypoint {
  double t = 0.0;                                            ///< s
  Eigen::Vector3d p_WH = Eigen::Vector3d::Zero();            ///< m, world
  Eigen::Quaterniond q_WH = Eigen::Quaterniond::Identity();  ///< unit, world

  /// The waypoint as a rigid transform.
  Eigen::Isometry3d pose() const;
};

/// A whole-robot trajectory for one object placement.
struct JointTrajectory {
  double theta_deg = 0.0;  ///< object orientation the trajectory is made for, deg
  /// The object centre on the table the trajectory is made for, world, m; empty: the scene's
  /// object centre (written only when set, so files of the fixed position are unchanged).
  std::optional<Eigen::Vector2d> object_xy;
  std::vector<TrajectorySample> samples;  ///< at least one, strictly increasing t
  std::vector<WristWaypoint> waypoints;   ///< optional, strictly increasing t

  /// Time of the last sample (s); 0 for an empty trajectory.
  double duration() const { return samples.empty() ? 0.0 : samples.back().t; }
  /// The object's placement: theta_deg in radians at object_xy.
  Placement placement() const { return {Radians(theta_deg), object_xy}; }
};

/// The command at time t: linear interpolation between the bracketing samples; the first
/// (last) sample before (after) the trajectory. Requires at least one sample.
TrajectorySample SampleAt(const JointTrajectory& trajectory, double t);

/// The same trajectory with every sample and waypoint time multiplied by `factor` (> 0).
JointTrajectory TimeScaled(const JointTrajectory& trajectory, double factor);

/// Parses a trajectory document: ReadJointTrajectory of the parsed text. `source` (a file
/// name) starts every message.
JointTrajectory ParseJointTrajectory(std::string_view json_text, const std::string& source);

/// Reads a trajectory object (a whole document, or a member of one such as a grasp file's
/// `trajectory`). Throws InputError (JsonReader's wording: source, field path such as
/// `samples[3].arm[2]`, expected and found value) when: `format` is not kJointTrajectoryFormat;
/// `theta_deg` is missing or not finite; `object_xy` is present but not two numbers within
/// +-5 m; `samples` is missing or empty; a sample lacks `t`,
/// `arm` or `hand`; `arm` does not hold 7 numbers or `hand` 16; a value is not a finite number
/// (JSON has no NaN, so a NaN written as null, a string or a bare NaN token is caught here);
/// time does not strictly increase; a waypoint's quaternion is not unit (|norm - 1| > 1e-6).
JointTrajectory ReadJointTrajectory(const JsonReader& object);

/// Checks every sample against the joint limits of the arm and the hand (closed ranges, with
/// `tol` radians of slack). Throws InputError "<source>: field '<prefix>samples[i].arm[j]':
/// expected a value within S3's limits [lo, hi] rad, found v" for the first offending value;
/// `field_prefix` is the trajectory's own path in its document (e.g. "trajectory.").
void CheckJointLimits(const JointTrajectory& trajectory, const ArmModel& arm, const HandModel& hand,
                      const std::string& source, double tol = 1e-9,
                      const std::string& field_prefix = "");

/// Reads, parses and limit-checks a trajectory file. Throws InputError naming the file.
JointTrajectory LoadJointTrajectory(const std::filesystem::path& path, const ArmModel& arm,
                                    const HandModel& hand);

/// The trajectory as a `graspsynth-trajectory/1` document: one sample per line, values
/// rounded to 1e-10, quaternions canonical (w >= 0).
std::string JointTrajectoryToJson(const JointTrajectory& trajectory);

/// Writes JointTrajectoryToJson atomically (temporary file + rename). Throws InputError.
void WriteJointTrajectory(const std::filesystem::path& path, const JointTrajectory& trajectory);

}  // namespace graspsynth
