#pragma once

/// @file
/// Replays for the browser viewer (`graspsynth view`): what the robot and the object do at
/// each instant of a trajectory file or of a demonstration log, as ViewerStates
/// (viewer/viewer_scene.hpp). A trajectory is played from its joint samples; a log's wrist
/// poses go through the analytic IK with a continuous arm angle, like the live teleoperation
/// loop does it; a trial record (simulation/trial_record.hpp) is played as simulated: the
/// joints, the object's pose and the contacts from the physics, and the outcome.

#include <optional>
#include <string>
#include <vector>

#include "kinematics/robot_description.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/joint_trajectory.hpp"
#include "scene/scene_model.hpp"
#include "simulation/trial_record.hpp"
#include "viewer/viewer_scene.hpp"

namespace graspsynth::viewer {

/// Joint samples to play (linear between samples) and, for a log, per sample: the object's
/// logged position, the button event and whether the IK reached the wrist pose.
struct ViewerReplay {
  std::string label;           ///< first part of every status line, e.g. "log FILE | theta ..."
  JointTrajectory trajectory;  ///< at least one sample
  std::vector<Eigen::Vector3d> p_WO;  ///< log: object centre per sample, world, m; else empty
  std::vector<DemoEvent> events;      ///< log: event per sample; else empty
  std::vector<bool> reached;          ///< log: false where the pose had no IK solution
  int unreached = 0;                  ///< number of false entries in `reached`
  /// trial: the object's pose per sample from the physics, world; else empty.
  std::vector<Eigen::Isometry3d> X_WO;
  /// trial: the object-hand contact points per sample, world, m; else empty.
  std::vector<std::vector<Eigen::Vector3d>> contacts;
  /// trial: the outcome, shown from the last sample on.
  std::optional<ViewerOutcome> outcome;

  /// Time of the first and the last sample, s.
  double start_time() const { return trajectory.samples.front().t; }
  double end_time() const { return trajectory.samples.back().t; }
};

/// A replay of `trajectory`'s samples, the object at rest at the trajectory's theta. `source`
/// (a file name) goes into the status line.
ViewerReplay ReplayOfTrajectory(JointTrajectory trajectory, const std::string& source);

/// A replay of a demonstration log. The first wrist pose that the arm reaches starts at a rest
/// configuration: the first branch (elbow up first, ArmBranch index order) on which the pose
/// has a solution, with the arm angle in the middle of its widest feasible arc. Every later
/// pose keeps that branch and takes the arm angle nearest the previous sample's
/// (SolveWristPose). A pose without a solution holds the previous configuration (the earliest
/// samples, before any reached pose, take the first reached one) and is marked in `reached`.
/// The hand follows the logged f0..f15.
ViewerReplay ReplayOfLog(const RobotModel& robot, const DemoLog& log);

/// A replay of a simulated trial: its frames' joints as the samples, the object's pose and the
/// contacts per frame, and its outcome ("success: REASON" or "FAILED (OUTCOME): REASON").
/// `source` (a file name) goes into the status line.
ViewerReplay ReplayOfTrial(const TrialRecord& record, const std::string& source);

/// The robot at rest (all joints zero), the object at theta = 0: for a viewer with nothing to
/// replay.
ViewerReplay RestReplay();

/// The state at replay time t (s, clamped to the samples' span): the joints by SampleAt; the
/// object at rest at the replay's theta, or for a log at its logged position (linear between
/// samples) turned by theta, or for a trial at its simulated pose (position linear, orientation
/// slerp between frames) with the contacts of the last frame at or before t and, at the last
/// frame, the outcome; the status line: the label, then for a log the last event at or before
/// t and a note while the arm holds an unreachable pose.
ViewerState ReplayStateAt(const ViewerReplay& replay, const SceneModel& scene, double t);

}  // namespace graspsynth::viewer
