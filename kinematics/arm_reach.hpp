#pragma once

/// @file
/// Where a flange target lies against the span of the arm (reference/robot.md 1.5 steps 1-2):
/// the wrist centre of the target against the shoulder centre, and the distances the arm spans
/// from its folded to its stretched elbow. The analytic IK (kinematics/arm_ik.hpp) takes its
/// shoulder-to-wrist vector from here; the commands say how far out of reach a target is.

#include <Eigen/Geometry>

#include "kinematics/arm_model.hpp"

namespace graspsynth {

/// The shoulder-to-wrist vector x_sw of a target X_W7 for DH frame 7 (world frame, m; the
/// flange itself on an arm whose DhJointMap is the identity, the PA-10): the wrist centre (d_wt
/// behind it along its z axis) less the shoulder centre (d_bs above the base).
Eigen::Vector3d ShoulderToWrist(const SrsLengths& lengths, const Eigen::Isometry3d& X_W7);

/// Where a flange target's wrist centre lies from the arm's shoulder centre, against the span of
/// the arm: the target is out of reach when `distance` is beyond `outer` or inside `inner`,
/// whatever the arm angle and the branch.
struct ArmReach {
  double distance = 0.0;  ///< |x_sw|, m
  double inner = 0.0;     ///< |d_se - d_ew|, m: the folded elbow
  double outer = 0.0;     ///< d_se + d_ew, m: the stretched elbow
};

/// The ArmReach of flange target X_WF (world frame, m); `distance` is not finite for a target
/// that is not.
ArmReach ReachOfTarget(const ArmModel& arm, const Eigen::Isometry3d& X_WF);

}  // namespace graspsynth
