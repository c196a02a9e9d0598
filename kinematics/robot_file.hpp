#pragma once

/// @file
/// The robot file (`graspsynth-robot/1`, docs/formats.md "Robot file"): a JSON file beside a
/// URDF that says which parts of the URDF are what. This reader reads the robot's name, its
/// URDF, where its base stands, the arm part and the hand part, and loads the whole robot
/// (LoadRobot); the collision and glove parts are left to later readers (their keys are
/// accepted and not read). models/pa10_gifu3.robot.json and models/iiwa14_allegro.robot.json
/// are the shipped ones.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"
#include "kinematics/robot_description.hpp"

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

/// A coupled finger joint of a robot file (hand.fingers[].coupled[]): joint = ratio * follows +
/// offset.
struct RobotFileCoupling {
  std::string joint;    ///< one of its finger's joints
  std::string follows;  ///< the joint it follows (an actuated hand joint)
  double ratio = 1.0;   ///< dimensionless
  double offset = 0.0;  ///< rad
};

/// A finger of a robot file (hand.fingers[]).
struct RobotFileFinger {
  std::string name;                 ///< unique in the hand
  std::string role;                 ///< "thumb" or "" (read and checked, not used yet)
  std::vector<std::string> joints;  ///< the URDF's revolute joints, proximal to distal
  std::string tip_link;             ///< the fingertip frame's link
  std::vector<RobotFileCoupling> coupled;
};

/// The hand part of a robot file.
struct RobotFileHand {
  std::string mount_link;                ///< the link of frame H, fixed below the arm's flange
  std::string palm_link;                 ///< the link of frame P, fixed below the mount
  std::string palm_frame = "gifu";       ///< the frames' convention: "gifu", the only one
  std::vector<RobotFileFinger> fingers;  ///< in the actuated order f0.. (coupled joints aside)
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
  std::optional<RobotFileHand> hand;  ///< the file's `hand`; LoadRobot needs it
  /// The file's `grasp` part, read against the hand by LoadRobot (ReadRobotGrasp).
  std::optional<JsonReader> grasp;
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

/// The whole robot of a robot file (`.json`) or a URDF (any other extension: LoadRobotModel).
/// A robot file gives: `name`; X_WB from its `base`; the arm as ArmFromRobotFile; X_FH, the
/// URDF's fixed joints from arm.flange_link down to hand.mount_link, and X_HP, those from the
/// mount down to hand.palm_link; the fingers of hand.fingers in order, each joint's parent the
/// link before (the palm for the first), its tip_link a fixed, massless child of the last
/// joint's link; the couplings of the file's `coupled` and the URDF's <mimic>s (where both give
/// one they must agree), each following an actuated hand joint; the actuated joints numbered
/// finger by finger, coupled ones left out; masses, inertias and collision shapes as
/// ParseRobotModel reads them. RobotModel::source is the robot file, the arm's and hand's the
/// URDF. Throws InputError naming the robot file, the field and the value: ParseRobotFile's and
/// ArmFromRobotFile's errors; no `hand`; a link or joint the URDF lacks; the mount or the palm
/// on the arm, or not fixed below the link before it (through massless frames only); a joint
/// on another link than the one before it, or named twice; a tip link that is not a fixed,
/// massless child of the last joint's link; a coupling that disagrees with the URDF's <mimic>,
/// follows a joint outside the hand or a coupled joint (a loop of couplings is named joint by
/// joint); a link with mass or geometry in neither the arm nor the hand; a hand HandModel
/// refuses (e.g. other than 16 actuated joints).
RobotModel LoadRobot(const std::filesystem::path& path);

/// The whole robot of a parsed robot file (LoadRobot after LoadRobotFile). Throws as LoadRobot.
RobotModel RobotFromFile(const RobotFile& file);

/// The robot of a `--robot` option (or of Python's Robot): "" gives the shipped default,
/// LoadRobotModel(DefaultRobotDescriptionPath()), exactly; anything else ResolveRobotPath then
/// LoadRobot. Throws as those.
RobotModel LoadRobotOption(std::string_view name_or_path);

/// Refuses a robot other than the PA-10 + Gifu Hand III (RobotModel::name kDefaultRobotName,
/// the shipped default) where `user` (a command, "--robot: run", or a Python call) reads data
/// made for that robot (`data`, e.g. "the grasp library": libraries, demonstrations and
/// trajectories do not name their robot yet). Throws InputError "<user> cannot use robot
/// '<name>' (<source>) yet: it reads <data>, made for the PA-10 + Gifu Hand III (pa10_gifu3)".
void RequireDefaultRobot(const RobotModel& robot, std::string_view user, std::string_view data);

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
