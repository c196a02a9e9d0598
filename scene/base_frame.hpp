#pragma once

/// @file
/// The scene seen from the robot's base. A scene file describes the study's world W (the table,
/// where the object stands); a robot stands in it at X_WB (RobotModel::X_WB, a robot file's
/// `base`). Everything downstream (IK targets, the collision scene, the ODE and MuJoCo worlds,
/// trajectories and reports) works in the arm's base frame B, so a scene is re-expressed in B
/// once, where it is combined with a robot (SimulationModel, SynthesisModel,
/// BuildScriptedGrasp). For a robot at the world's origin (the PA-10: X_WB = I) nothing is
/// computed and the scene keeps its bits.

#include <Eigen/Geometry>

#include "scene/scene_model.hpp"

namespace graspsynth {

/// `scene` re-expressed in the frame B at X_WB (pose of B in the study's world W, m): the
/// table's top and centre, the object's centre and yaw offset; the grasp region (about the
/// object centre) and the object (in its own frame) are unchanged. Sets scene.X_WS = X_WB. A
/// scene already in that frame (scene.X_WS == X_WB, exactly) is returned as it is, so the call
/// may be repeated. Throws InputError naming the scene when B is tilted or turned about the
/// vertical relative to the scene's frame by more than 1e-9 rad (the table is an axis-aligned
/// box: a turned base is not supported yet).
SceneModel SceneInBaseFrame(SceneModel scene, const Eigen::Isometry3d& X_WB);

/// A table point given in the study's world W (an object centre asked for with --at, m)
/// expressed in the scene's frame (scene.X_WS): returned unchanged when that is W.
Eigen::Vector2d TablePointInScene(const SceneModel& scene, const Eigen::Vector2d& xy_W);

}  // namespace graspsynth
