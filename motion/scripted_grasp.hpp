#pragma once

/// @file
/// A scripted (hand-made, not learned) grasp-and-lift trajectory for the pan of the scene:
/// reach -> approach -> close -> settle -> lift -> hold, as a joint trajectory through the
/// analytic IK with a continuous arm angle (motion/joint_space.hpp). examples/grasp_60deg.json
/// is made with it; later stages (the synthetic operator) reuse it to generate demonstrations.
///
/// The grasp (reference/ode.md): the palm faces down above the handle, the hand's long axis
/// lies across it, the fingertips press the handle's far vertical face and the thumb tip its
/// near face, so that contact normals are horizontal and only friction carries the weight.
/// The wrist is placed from where the handle should sit in the hand: GraspWristPose puts the
/// point `bar_in_hand` of frame H on the handle's axis, `grasp_radius` from the object centre.

#include <optional>
#include <string>

#include "kinematics/robot_description.hpp"
#include "kinematics/robot_grasp.hpp"
#include "motion/joint_trajectory.hpp"
#include "scene/rest_pose.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// Everything that shapes a scripted grasp. Lengths in m, angles in rad, times in s.
struct ScriptedGraspOptions {
  double theta_deg = 60.0;  ///< object orientation, deg
  /// Where along the handle the hand closes: distance from the object centre, m. Close to the
  /// pan: the pan's weight pulls 0.2 m (handle end) to 0.06 m (here) from the grasp, and the
  /// torque about the axis across the handle is resisted only by friction couples between
  /// fingertips spread along it (ODE has no torsional friction). Measured with the default
  /// hand shapes: 0.12-0.15 m hold level, from 0.17 m the pan pitches down and slips.
  double grasp_radius = 0.14;
  /// Where the handle's axis lies in the hand-mount frame H at the grasp: depth below the
  /// palm (x), along the thumb side (y), toward the fingertips (z), m. Unset: the robot's
  /// (RobotGraspOf: its robot file's `grasp.bar_in_hand_m`; the PA-10's is the pinch of
  /// models/README.md, a 24 mm bar between the distal pads of the fingers and the thumb's tip:
  /// the wrist ends up 0.131 m above the table).
  std::optional<Eigen::Vector3d> bar_in_hand;
  /// Hand yaw about the vertical away from "across the handle", rad.
  double yaw = 0.0;
  /// Wrist side: +1 puts the wrist on the right of the handle (seen along the handle from the
  /// pan; the hand's thumb side toward the pan), -1 on the left (little finger toward the pan).
  int side = +1;
  /// Pre-grasp pose = grasp pose moved up by pregrasp_up (world z) and back along -z_H by
  /// pregrasp_back, m.
  double pregrasp_up = 0.07;
  double pregrasp_back = 0.02;
  /// Finger shapes f0..f15 (rad): open during reach and approach, closed at the grasp. Unset:
  /// the robot's (RobotGraspOf: its robot file's `grasp.open_deg`, `grasp.closed_deg`).
  std::optional<HandVector> open;
  std::optional<HandVector> closed;
  /// Keep the hand open at the grasp (the closed hand is the open one): a trajectory that must
  /// fail.
  bool keep_open = false;
  double reach_duration = 2.0;     ///< rest -> pre-grasp
  double approach_duration = 1.0;  ///< pre-grasp -> grasp
  double close_duration = 0.8;     ///< open -> closed at the grasp pose
  double settle_duration = 0.3;    ///< held closed before the lift
  double lift_duration = 1.0;      ///< straight up by lift_height
  double lift_height = 0.10;
  double end_duration = 0.2;    ///< held at the top (the trial's own hold comes after)
  double sample_period = 0.02;  ///< spacing of the trajectory samples
  /// Arm configuration at the start (rad); unset picks DefaultRestConfiguration.
  std::optional<Vector7d> rest;

  bool IsValid(std::string* why) const;
};

/// The scripted grasp's hand shapes and grip for `robot`: the options' where set, else the
/// robot's (RobotGraspOf); with keep_open the closed hand is the open one. Throws RobotGraspOf's
/// InputError.
RobotGrasp ScriptedGraspShapes(const RobotModel& robot, const ScriptedGraspOptions& options);

/// The wrist pose X_BH of the grasp in the robot's base frame B (see the file comment; `scene`
/// is re-expressed in B, scene/base_frame.hpp).
Eigen::Isometry3d GraspWristPose(const RobotModel& robot, const SceneModel& scene,
                                 const ScriptedGraspOptions& options);

/// The built trajectory, or why it could not be built.
struct ScriptedGraspResult {
  bool ok = false;
  std::string message;         ///< why not, when !ok
  JointTrajectory trajectory;  ///< samples and the waypoints rest, pre-grasp, grasp, closed, lifted
  Eigen::Isometry3d X_WH_grasp = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WH_pregrasp = Eigen::Isometry3d::Identity();
};

/// Builds the scripted trajectory. Throws InputError for invalid options and for a scene whose
/// default rest pose is out of reach (DefaultRestConfiguration, scene/rest_pose.hpp); an
/// unreachable pose or a joint jump is a result with ok = false.
ScriptedGraspResult BuildScriptedGrasp(const RobotModel& robot, const SceneModel& scene,
                                       const ScriptedGraspOptions& options);

}  // namespace graspsynth
