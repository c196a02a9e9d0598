#pragma once

/// @file
/// Generalization of grasping motions by interpolation (paper IV-A, IV-B): two motions
/// demonstrated at object orientations theta1 < theta2 are resampled to the same number of
/// waypoints and blended waypoint by waypoint at t = (theta - theta1) / (theta2 - theta1):
/// wrist orientation by slerp, wrist position relative to the object centre by aslerp
/// (eqs. 1-2), fingers by the convex blend (eq. 4).

#include <vector>

#include "motion/grasping_motion.hpp"
#include "motion/resample.hpp"

namespace graspsynth {

/// Options of BlendMotions.
struct BlendOptions {
  /// Waypoints of the blended motion (both inputs are resampled to it), >= 2.
  int waypoints = 60;
  /// Spacing of the resampled waypoints.
  ResampleMode resample = ResampleMode::kNormalizedTime;

  /// False (with the reason in `why`) when an option is out of range.
  bool IsValid(std::string* why) const;
};

/// The interpolation parameter t = (theta - theta1) / (theta2 - theta1) of orientation theta
/// between two demonstrated orientations (radians; theta1 != theta2).
double BlendParameter(double theta, double theta1, double theta2);

/// The blend of m1 (t = 0) and m2 (t = 1): positions relative to each motion's object centre
/// are aslerp-ed and placed at the blended centre, orientations slerp-ed, fingers and times
/// blended linearly, theta = (1 - t) theta1 + t theta2. At t = 0 and t = 1 the result is the
/// resampled m1 or m2 exactly. Requires both motions well formed and valid options.
GraspingMotion BlendMotions(const GraspingMotion& m1, const GraspingMotion& m2, double t,
                            const BlendOptions& options = {});

/// The paper's blend generalized to several motions (demonstrations at the vertices of a
/// placement cell, solver/placement_cell.hpp) with weights w_i >= 0 summing to 1: every motion
/// is resampled to options.waypoints and, waypoint by waypoint, the wrist position relative to
/// each motion's object centre is blended by WeightedAslerp and placed at the weighted centre,
/// the wrist orientation by WeightedSlerp, fingers and times by the weighted mean; theta is the
/// weighted mean. A weight of 1 returns that resampled motion exactly; two motions with weights
/// (1 - t, t) give BlendMotions(m1, m2, t) (to 1e-12). Requires well-formed motions, valid
/// options and valid weights.
GraspingMotion BlendMotionsWeighted(const std::vector<const GraspingMotion*>& motions,
                                    const std::vector<double>& weights,
                                    const BlendOptions& options = {});

}  // namespace graspsynth
