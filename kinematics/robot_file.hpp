#pragma once

/// @file
/// The robot file (`graspsynth-robot/1`, docs/formats.md "Robot file"): a JSON file beside a
/// URDF that says which parts of the URDF are what. This reader reads the robot's name, its
/// URDF and the arm part; the hand, collision and glove parts are left to later readers (their
/// keys are accepted and not read). models/pa10_gifu3.robot.json and
/// models/iiwa14_allegro.robot.json are the shipped ones.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"

namespace graspsynth {

/// The servo of a part (arm.servo, hand.servo): read and checked, not used yet.
struct RobotFileServo {
  double position_gain = 20.0;   ///< 1/s: joint velocity = v_ff + gain (target - q)
  double force_cap_scale = 1.0;  ///< the motors' force caps are the URDF efforts times this
};

/// The arm part of a robot file.
struct RobotFileArm {
  std::string base_link;          ///< the URDF link whose frame is the arm's base (world) frame
  std::string flange_link;        ///< the URDF link whose frame is the flange F
  std::string ik = "srs";         ///< the IK: "srs" (the analytic arm-angle IK), the only one
  double srs_tolerance_m = 1e-6;  ///< m, ArmChainOptions::srs_tolerance_m
  RobotFileServo servo;
};

/// What a robot file says (the parts read so far).
struct RobotFile {
  std::string source;          ///< the robot file, for messages
  std::string name;            ///< the robot's name
  std::string comment;         ///< the file's `comment`: what the robot is ("" when it has none)
  std::filesystem::path urdf;  ///< the URDF: the file's `urdf` relative to its folder
  /// Pose of the arm's base frame B in the study's world frame W: the file's `base`
  /// ({"position_m": [x, y, z], "yaw_deg": a}: a turn by a about W's z, then the shift); identity
  /// when it has none.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  RobotFileArm arm;
};

/// Parses a robot file's text (`json`; `source` names it in messages; `folder` is where its
/// relative URDF path starts). Throws InputError in JsonReader's wording ("<source>: field
/// '<path>': expected <what>, found <value>") when it is not JSON, the format is not
/// `graspsynth-robot/1`, a key is unknown (top level, base, arm, arm.servo), `name` or `urdf` is
/// not a non-empty string, `base.position_m` is not 3 numbers each in [-10, 10] m or
/// `base.yaw_deg` (optional, 0 by default) not in [-180, 180], `arm.base_link` / `arm.flange_link`
/// is not a non-empty string or both are the same, `arm.ik` is not "srs", `arm.srs_tolerance_m` is
/// not in (0, 0.01], or a servo number is not positive.
RobotFile ParseRobotFile(std::string_view json, const std::string& source,
                         const std::filesystem::path& folder);

/// Reads and parses the robot file at `path` (ParseRobotFile; the URDF is relative to the
/// file's folder). Throws InputError when it cannot be read, and ParseRobotFile's errors.
RobotFile LoadRobotFile(const std::filesystem::path& path);

/// The arm of the robot file at `path`: its URDF's chain from arm.base_link to arm.flange_link
/// (ReadArmChain) checked and mapped onto the DH table by ArmModel with arm.srs_tolerance_m.
/// The hand is not loaded. Throws InputError: LoadRobotFile's errors; the URDF cannot be read
/// or is not a URDF; a named link does not exist ("<file>: field 'arm.flange_link': expected a
/// link of '<urdf>', found \"...\""); the chain is not one or has another number of revolute
/// joints ("<file>: fields 'arm.base_link', 'arm.flange_link': expected ..."); the arm is not
/// SRS within the tolerance, or matches no joint sign and offset of the DH table ("<file>:
/// field 'arm.ik': expected an SRS arm ..., found <the URDF's joints and the miss, in m and
/// mm>").
ArmModel LoadArmFromRobotFile(const std::filesystem::path& path);

/// The arm of a parsed robot file (LoadArmFromRobotFile after its LoadRobotFile): reads the URDF
/// at file.urdf. Throws as LoadArmFromRobotFile.
ArmModel ArmFromRobotFile(const RobotFile& file);

/// A robot shipped with graspsynth: the robot file DataDirectory()/models/<name>.robot.json.
struct ShippedRobot {
  std::string name;            ///< the robot file's `name`, which is its file's name
  std::filesystem::path file;  ///< the robot file
  std::string comment;         ///< the robot file's `comment`
};

/// The name of the robot every command uses when it is given none: "pa10_gifu3".
inline constexpr std::string_view kDefaultRobotName = "pa10_gifu3";

/// The shipped robots, sorted by name: every models/*.robot.json of DataDirectory(), each
/// parsed (ParseRobotFile). Throws InputError when models/ cannot be listed, when one of them
/// does not parse (its error), or when a file's `name` is not its file's name ("<file>: field
/// 'name': expected \"<stem>\" (the file's name), found ...").
std::vector<ShippedRobot> ShippedRobots();

/// The robot file or URDF that `--robot` names: a shipped robot's name (ShippedRobots(), e.g.
/// "iiwa14_allegro") gives its robot file; anything with a '/' or ending in ".json" or ".urdf"
/// is a path and is returned as it is. Throws InputError for any other word, naming the
/// shipped robots ("--robot: expected a shipped robot (pa10_gifu3, ...; 'graspsynth robots'
/// lists them) or a robot file's path, found \"...\"").
std::filesystem::path ResolveRobotPath(std::string_view name_or_path);

}  // namespace graspsynth
