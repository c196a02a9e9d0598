#pragma once

/// @file
/// The rest pose of the arm: where a synthesized reach, a teleoperation trial and a replayed
/// demonstration start when nothing else gives the start configuration.

#include <Eigen/Geometry>

#include "kinematics/robot_description.hpp"
#include "kinematics/types.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// A rest configuration of the arm for a grasp with wrist orientation R_WH: the wrist 0.60 m
/// from the base toward the object centre and 0.30 m above the table, turned like the grasp
/// but pitched 30 deg fingertips-down (about y_H), so that the reach mostly translates; branch
/// (+1, +1, +1), arm angle in the middle of its widest feasible arc. Throws InputError naming
/// the scene (scene.source) when that pose is out of the arm's reach (a scene whose table or
/// object is placed where the rest pose cannot be reached).
Vector7d DefaultRestConfiguration(const RobotModel& robot, const SceneModel& scene,
                                  const Eigen::Matrix3d& R_WH);

}  // namespace graspsynth
