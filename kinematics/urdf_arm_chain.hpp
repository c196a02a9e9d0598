#pragma once

/// @file
/// The parts of a URDF named by a robot file (kinematics/robot_file.hpp): the arm chain between
/// two links (arm.base_link, arm.flange_link), read into the parts ArmModel takes, and the hand
/// (hand.mount_link, hand.palm_link, hand.fingers), read into the parts HandModel takes.
/// Implemented beside the PA-10 loader in robot_description.cpp (the same URDF reading and
/// checks).

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/arm_model.hpp"
#include "kinematics/hand_model.hpp"

namespace graspsynth {

/// Which arm chain of a URDF to read (ReadArmChain) and how to name its parts in messages.
struct ArmChainNames {
  std::string base_link;    ///< the arm's base link (its frame is the world frame)
  std::string flange_link;  ///< the flange link (its frame is the flange F)
  /// Message prefixes for a bad base link, a bad flange link and a bad chain between them, e.g.
  /// "robot.json: field 'arm.base_link'"; the URDF's source when empty.
  std::string base_where, flange_where, chain_where;
};

/// The parts of a URDF's arm chain, for ArmModel: the base, the 7 revolute joints with the
/// fixed joints between them folded into their X_PJ, their child links, and the fixed joints
/// after the last one as the flange's pose in link 7 (ArmChainOptions::X_7F).
struct ArmChain {
  RigidLink base;
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
  Eigen::Isometry3d X_7F = Eigen::Isometry3d::Identity();  ///< flange F in link 7
};

/// Reads the arm chain of a URDF document (`urdf_xml`; `source` names it): the path of joints
/// from names.base_link down to names.flange_link, which must be exactly 7 revolute joints
/// (with limits, no <mimic>) and any number of fixed joints. Does not check the SRS structure
/// (ArmModel does). Throws InputError when the text is not a URDF (ParseRobotModel's reasons);
/// when a named link does not exist ("<where>: expected a link of '<source>', found
/// \"<name>\""); when the flange link is not below the base link, the chain has another
/// number of revolute joints or a joint of another type; when a link joined by a fixed joint
/// inside the chain has mass or collision geometry (merging fixed links is not supported yet);
/// when a link of a revolute joint has no positive mass or a non-physical inertia.
ArmChain ReadArmChain(std::string_view urdf_xml, const std::string& source,
                      const ArmChainNames& names);

/// A passive hand joint that follows another one (a robot file's fingers[].coupled[]):
/// joint = ratio * follows + offset.
struct CoupledJointNames {
  std::string joint;    ///< the passive joint, one of its finger's joints
  std::string follows;  ///< the joint it follows, an actuated hand joint
  double ratio = 1.0;   ///< dimensionless
  double offset = 0.0;  ///< rad
  std::string where;    ///< message prefix, e.g. "robot.json: field 'hand.fingers[1].coupled[0]'"
};

/// One finger named by a robot file (hand.fingers[i]).
struct FingerPartNames {
  std::string name;                 ///< the finger's name
  std::vector<std::string> joints;  ///< its revolute joints, proximal to distal
  std::string tip_link;             ///< the fingertip frame: a fixed massless child of the last
  std::vector<CoupledJointNames> coupled;
  /// Message prefixes for the finger ("<file>: field 'hand.fingers[i]'"), each of its joints
  /// (`joints_where[k]`) and its tip link.
  std::string where, tip_where;
  std::vector<std::string> joints_where;
};

/// Which hand of a URDF to read (ReadRobotParts) and how to name its parts in messages.
struct HandNames {
  std::string mount_link;  ///< frame H: fixed below the arm's flange link
  std::string palm_link;   ///< frame P: fixed below the mount link
  std::vector<FingerPartNames> fingers;
  std::string mount_where, palm_where;  ///< message prefixes for the two links
  std::string where;                    ///< message prefix for the hand as a whole
};

/// The parts of a URDF's robot: its name, the arm chain (ReadArmChain) and the hand, for
/// ArmModel and HandModel.
struct RobotParts {
  std::string name;  ///< the URDF's <robot name=...>
  ArmChain arm;
  Eigen::Isometry3d X_FH = Eigen::Isometry3d::Identity();  ///< the mount H in the flange F
  RigidLink mount, palm;
  Eigen::Isometry3d X_HP = Eigen::Isometry3d::Identity();  ///< the palm P in the mount H
  std::vector<Finger> fingers;                             ///< actuated joints numbered in order
};

/// Reads a URDF document's whole robot as a robot file names it: the arm chain (ReadArmChain's
/// reading and errors); X_FH, the fixed joints from the arm's flange link down to the mount
/// link, and X_HP, those from the mount link down to the palm link (each link between them a
/// massless frame without geometry); the fingers in order, each joint's parent the link before
/// (the palm for the first), the tip link a fixed, massless child of the last joint's link
/// without geometry or children; the couplings of `coupled` and of the URDF's <mimic>s (where
/// both give one they must agree), each following an actuated hand joint; the actuated joints
/// numbered finger by finger. Masses, inertias and collision shapes as ParseRobotModel reads
/// them. Throws InputError naming the `where` of the part and the value when a link or joint
/// does not exist, the mount or palm is a link of the arm or not below the link before it, a
/// chain is not one, a joint is named twice, a coupling is not a joint of its finger, follows a
/// coupled joint (a loop of couplings names its joints) or disagrees with the URDF's <mimic>,
/// and when a link with mass or geometry is part of neither the arm nor the hand.
RobotParts ReadRobotParts(std::string_view urdf_xml, const std::string& source,
                          const ArmChainNames& arm, const HandNames& hand);

}  // namespace graspsynth
