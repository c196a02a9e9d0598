#pragma once

/// @file
/// Loads the robot description (a URDF, models/pa10_gifu3.urdf) into the immutable models of the
/// PA-10-7C arm and the Gifu Hand III. The URDF's names, frames and conventions (capsules, the
/// hand mount, the actuated hand joint order) are documented in models/README.md.

#include <filesystem>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/robot_grasp.hpp"

namespace graspsynth {

/// The whole robot: the arm, the fixed hand mount and the hand.
struct RobotModel {
  /// The description it was read from (a file name) for messages.
  std::string source;
  ArmModel arm;
  /// Pose of the hand-mount frame H in the flange frame F (the URDF joint `hand_mount`).
  Eigen::Isometry3d X_FH = Eigen::Isometry3d::Identity();
  HandModel hand;
  /// The robot's name: a URDF's `<robot name=...>` ("pa10_gifu3" for the shipped URDF), a robot
  /// file's `name`.
  std::string name;
  /// Pose of the arm's base frame B in the study's world frame W (m; identity for the PA-10).
  /// A robot file may give it (its `base`); a URDF alone gives identity.
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  /// The scripted grasp's hand shapes and grip (a robot file's `grasp` part); empty when the
  /// robot was loaded from its URDF alone (RobotGraspOf then reads the shipped robot file).
  std::optional<RobotGrasp> grasp;
};

/// Reads and checks the robot description at `path` (see ParseRobotModel). Throws InputError
/// naming the file when it cannot be read, and every error of ParseRobotModel.
RobotModel LoadRobotModel(const std::filesystem::path& path);

/// Parses a URDF document (`urdf_xml`; `source` names it in messages) with urdfdom and builds
/// the robot model. The library never prints: urdfdom's console output is captured while it
/// parses and becomes part of the message. Throws InputError whose message starts with `source`
/// and names the element when:
/// - the text is not XML or not a URDF document (urdfdom's reason, e.g. the joint whose limits
///   are missing), or a value does not parse;
/// - the root link is not `base_link`, or a link is not part of the PA-10 + Gifu model;
/// - an arm joint S1 S2 S3 E1 E2 W1 W2 is missing, not revolute (continuous and fixed are
///   rejected), without limits, coupled, or does not link base_link -> S1_link -> S2_link ->
///   S3_link -> E1_link -> E2_link -> W1_link -> W2_link in this order;
/// - the arm is not the SRS chain of reference/robot.md 1.3 (ArmModel's checks);
/// - the fixed joint `hand_mount` (W2_link -> hand_mount_link) or the fixed joint to `palm` is
///   missing or of another type;
/// - a revolute joint on the palm is not named `<finger>_j1`, or a finger's chain is not palm ->
///   `<finger>_j1` -> `<finger>_j2` -> ... (as many as the URDF has, each revolute with limits)
///   -> `<finger>_tip` (fixed); the fingers are the palm's `<finger>_j1` joints in the
///   document's order, their actuated joints (those without a <mimic>) numbered f0, f1, ... in
///   that order, and a joint with a <mimic> follows the joint it names, which must be an actuated
///   hand joint (the Gifu: each DIP j4 of index, middle, ring, little mimics its PIP j3);
/// - the hand's model is refused (HandModel's checks), e.g. it has other than 16 actuated joints;
/// - a link other than a fingertip frame has no positive mass or a non-physical inertia, or a
///   fingertip frame has mass or geometry;
/// - a collision geometry is a mesh (only box, cylinder, sphere and capsules are used).
/// A <collision> whose name starts with "capsule" and holds a <cylinder> is a capsule: the
/// cylinder's length is the straight part, hemispherical caps are added beyond it. Visual
/// elements are not read.
RobotModel ParseRobotModel(std::string_view urdf_xml, const std::string& source);

/// Path of the shipped robot description: $GRASPSYNTH_DATA_DIR/models/pa10_gifu3.urdf when the
/// environment variable is set and not empty, else the source tree's models/pa10_gifu3.urdf.
std::filesystem::path DefaultRobotDescriptionPath();

}  // namespace graspsynth
