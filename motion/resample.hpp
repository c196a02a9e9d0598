#pragma once

/// @file
/// Sampling and resampling of grasping motions (paper IV-B: the two motions to be blended are
/// first resampled to the same number of waypoints).

#include "motion/grasping_motion.hpp"

namespace graspsynth {

/// The motion at time t (s, clamped to [0, duration]): position and fingers linear between the
/// neighbouring waypoints, orientation by slerp.
MotionWaypoint SampleAt(const GraspingMotion& motion, double t);

/// How the new waypoints are spaced.
enum class ResampleMode {
  kNormalizedTime,  ///< evenly in time (the default, and the paper's reading)
  kArcLength,       ///< evenly along the wrist's path length; falls back to time for a wrist
                    ///< that does not move
};

/// The motion with `count` (>= 2) waypoints spread evenly by `mode`; the first and last
/// waypoints are the original pre-grasp and grasp poses exactly, and each new waypoint keeps the
/// time at which the original motion passed it. Requires IsWellFormed(motion).
GraspingMotion Resample(const GraspingMotion& motion, int count,
                        ResampleMode mode = ResampleMode::kNormalizedTime);

}  // namespace graspsynth
