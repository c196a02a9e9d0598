#pragma once

/// @file
/// Perturbed replays of a joint trajectory for robustness evaluation (paper IV-B: time scaling
/// and waypoint noise).
///
/// How the noise is applied (all draws from one SplitMix64 stream, in this order):
/// 1. time scale s ~ U[time_scale_min, time_scale_max]; every sample and waypoint time is
///    multiplied by s (the whole motion - reach, grasp and lift - runs slower or faster).
/// 2. noise knots: the trajectory's Cartesian waypoint times when it has waypoints, else
///    evenly spaced every knot_interval seconds from 0 to the end (both included). At each
///    knot, in knot order: a wrist offset dp ~ N(0, position_sigma^2) per world axis, a wrist
///    rotation vector dr ~ N(0, orientation_sigma^2) per world axis, and a finger offset
///    df_k ~ N(0, finger_sigma^2) per actuated hand joint.
/// 3. between knots the offsets blend with the smooth step 3u^2 - 2u^3 (zero rate at every
///    knot); before the first and after the last knot they are constant.
/// 4. each sample's wrist pose X_WH = FK(arm) X_FH becomes (p + dp, exp(dr) R); the arm joints
///    are solved by the analytic IK on the sample's branch at its arm angle (moved into the
///    nearest feasible arc when the perturbed pose needs it; 2 pi-equivalents nearest the
///    previous perturbed sample); fingers become f + df clamped to their limits.
/// A perturbed pose with no IK solution within the joint limits makes the replay infeasible
/// (a failed trial: the robot cannot execute it).

#include <cstdint>
#include <string>

#include "kinematics/robot_description.hpp"
#include "motion/joint_trajectory.hpp"
#include "simulation/physics_perturbation.hpp"

namespace graspsynth {

class SplitMix64;

/// Noise and time scaling of a perturbed replay. Defaults: reference/ode.md and the issue.
struct PerturbationOptions {
  double time_scale_min = 0.7;              ///< 1
  double time_scale_max = 1.3;              ///< 1
  double position_sigma = 0.005;            ///< m, per world axis
  double orientation_sigma = Radians(2.0);  ///< rad, per world axis (rotation vector)
  double finger_sigma = Radians(2.0);       ///< rad, per actuated finger joint
  double knot_interval = 0.5;               ///< s, noise knots without waypoints
  /// Ranges of the physics each replay draws after the motion's noise
  /// (simulation/physics_perturbation.hpp); PerturbTrajectory itself does not read them.
  PhysicsPerturbationOptions physics;

  /// Multiplies the motion's noise (position, orientation and finger sigmas) by `factor`
  /// (`generalize --noise-scale`); the time scaling and the physics are left as they are.
  void ScaleMotionNoise(double factor) {
    position_sigma *= factor;
    orientation_sigma *= factor;
    finger_sigma *= factor;
  }

  bool IsValid(std::string* why) const;
};

/// A perturbed trajectory, or why the robot cannot play it.
struct PerturbedTrajectory {
  bool ok = false;
  std::string message;         ///< why not (the first pose without an IK solution), when !ok
  double time_scale = 1.0;     ///< the drawn time scale
  JointTrajectory trajectory;  ///< the perturbed samples (and waypoints), when ok
};

/// Draws one perturbed replay of `nominal` from `rng` (see the file comment). Throws
/// InputError for invalid options.
PerturbedTrajectory PerturbTrajectory(const RobotModel& robot, const JointTrajectory& nominal,
                                      const PerturbationOptions& options, SplitMix64& rng);

}  // namespace graspsynth
