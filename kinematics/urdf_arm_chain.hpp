#pragma once

/// @file
/// The arm chain of a URDF named by two links (the robot file's arm.base_link and
/// arm.flange_link, kinematics/robot_file.hpp), read into the parts ArmModel takes. Implemented
/// beside the PA-10 loader in robot_description.cpp (the same URDF reading and checks).

#include <array>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"

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

}  // namespace graspsynth
