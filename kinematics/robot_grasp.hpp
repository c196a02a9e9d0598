#pragma once

/// @file
/// The robot file's `grasp` part (docs/formats.md "Robot file"): the hand shapes and the grip
/// geometry of the scripted grasp (motion/scripted_grasp.hpp), which depend on the hand and so
/// are data, not code. models/pa10_gifu3.robot.json carries the Gifu Hand III's, as they were
/// in the code before; models/iiwa14_allegro.robot.json the Allegro Hand's.
///
///     "grasp": {
///       "bar_in_hand_m": [0.086, 0.0, 0.103],
///       "open_deg": {"thumb_j1": 90, "thumb_j3": 15, "index_j1": -20, ...},
///       "closed_deg": {"thumb_j1": 90, "thumb_j3": 30, ...}
///     }
///
/// A hand shape names actuated joints (HandModel::actuated_names) with their angles in degrees;
/// a joint it does not name is at 0.

#include <filesystem>
#include <optional>

#include "common/json_reader.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/types.hpp"

namespace graspsynth {

struct RobotModel;

/// The scripted grasp's hand-specific part.
struct RobotGrasp {
  /// The open hand (reach and approach), f0..f15, rad.
  HandVector open = HandVector::Zero();
  /// The closed hand (commanded at the grasp; the fingers stall on the handle), f0..f15, rad.
  HandVector closed = HandVector::Zero();
  /// Where the handle's axis lies in the hand-mount frame H at the grasp, m: depth below the
  /// palm (x_H), along the thumb side (y_H), toward the fingertips (z_H).
  Eigen::Vector3d bar_in_hand = Eigen::Vector3d::Zero();
};

/// Reads a robot file's `grasp` object (`grasp`, a JsonReader on it) for `hand`: `bar_in_hand_m`
/// (3 numbers, each in [-0.5, 0.5] m), `open_deg` and `closed_deg` (objects: an actuated joint's
/// name to its angle in degrees; radians are degrees times kDeg). Throws InputError in
/// JsonReader's wording ("<file>: field 'grasp.open_deg.<joint>': expected ..., found ...")
/// for an unknown key, a missing part, a name that is not an actuated joint of the hand (a
/// coupled joint follows its source), or an angle outside the joint's limits (1e-6 rad slack).
RobotGrasp ReadRobotGrasp(const JsonReader& grasp, const HandModel& hand);

/// The `grasp` part of the robot file at `path` for `hand` (ReadRobotGrasp), or nothing when
/// the file has none. Throws InputError when the file cannot be read or is not JSON, and
/// ReadRobotGrasp's errors.
std::optional<RobotGrasp> LoadRobotGrasp(const std::filesystem::path& path, const HandModel& hand);

/// The scripted grasp's part of `robot`: robot.grasp when its robot file gave one; else the
/// `grasp` part of the shipped robot file of the robot's name
/// (DataDirectory()/models/<robot.name>.robot.json: a URDF loaded alone, LoadRobotModel, is taken
/// for the shipped robot of its name, so the PA-10's URDF gets models/pa10_gifu3.robot.json's).
/// Throws InputError naming the robot when there is none, and LoadRobotGrasp's errors.
RobotGrasp RobotGraspOf(const RobotModel& robot);

}  // namespace graspsynth
