#pragma once

/// @file
/// The grasping motion of the paper (section III-B): the ordered waypoints W_i = {x_i, q_i, f_i}
/// of the wrist and fingers from the pre-grasp pose (first sample inside the grasp workspace
/// region) to the grasp pose (the grasp-button sample).

#include <string>
#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

/// One waypoint of a grasping motion.
struct MotionWaypoint {
  double t = 0.0;                                  ///< s, time since the pre-grasp pose
  Eigen::Vector3d p_WH = Eigen::Vector3d::Zero();  ///< wrist (hand mount) position, world, m
  Eigen::Quaterniond q_WH = Eigen::Quaterniond::Identity();  ///< wrist orientation, unit
  HandVector f = HandVector::Zero();                         ///< finger joints f0..f15, rad
};

/// A grasping motion: pre-grasp first, grasp last, times non-decreasing from 0.
struct GraspingMotion {
  double theta = 0.0;                              ///< object orientation, rad
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();  ///< object centre at rest, world, m
  std::vector<MotionWaypoint> waypoints;
  std::string source;  ///< provenance (file, trial), for reports

  /// Duration from the pre-grasp to the grasp pose, s (0 when empty).
  double duration() const { return waypoints.empty() ? 0.0 : waypoints.back().t; }
  const MotionWaypoint& pregrasp() const { return waypoints.front(); }
  const MotionWaypoint& grasp() const { return waypoints.back(); }
};

/// The wrist pose X_WH of waypoint `w` (rotation from its quaternion, translation p_WH).
Eigen::Isometry3d WaypointPose(const MotionWaypoint& w);

/// Checks what every producer of a GraspingMotion must guarantee: at least two waypoints,
/// the first at t = 0, times strictly increasing, finite values and unit quaternions (1e-9).
/// Returns false and says why in `why` otherwise.
bool IsWellFormed(const GraspingMotion& motion, std::string* why);

}  // namespace graspsynth
