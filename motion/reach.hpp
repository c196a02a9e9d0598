#pragma once

/// @file
/// Reaching motions (paper IV-C): from the robot's current wrist pose to the pre-grasp pose of
/// a grasping motion. The paper's method: cubic-spline positions and slerp orientation; its
/// suggested alternative: a discrete dynamic movement primitive (DMP). Also the lift that
/// follows the grasp.

#include <string>
#include <vector>

#include "motion/grasping_motion.hpp"

namespace graspsynth {

/// Samples of a Cartesian wrist-and-finger trajectory, times strictly increasing.
using CartesianPath = std::vector<MotionWaypoint>;

/// The minimum-jerk profile 10u^3 - 15u^4 + 6u^5 of u clamped to [0, 1]: 0 and 1 at the ends with
/// zero velocity and acceleration there; its peak slope is 1.875 (at u = 0.5).
double MinimumJerk(double u);

/// Options of the spline reach.
struct SplineReachOptions {
  double duration = 2.0;            ///< s, from the start pose to the pre-grasp pose
  double sample_period = 1.0 / 60;  ///< s, spacing of the returned samples
  /// Intermediate wrist positions (world, m) the path passes through, in order; their times
  /// are spread in proportion to the chord lengths.
  std::vector<Eigen::Vector3d> via_points;

  bool IsValid(std::string* why) const;
};

/// A clamped cubic spline through the start position, the via points and the pre-grasp
/// position, starting at rest and arriving with velocity `v_end` (world, m/s; the grasping
/// motion's initial velocity, so that the two join smoothly). The orientation and the fingers
/// move from the start to the pre-grasp values along the smooth profile 3u^2 - 2u^3 (slerp for
/// the orientation). Sample times run from start.t to start.t + duration; the last sample is
/// the pre-grasp pose exactly.
CartesianPath SplineReach(const MotionWaypoint& start, const MotionWaypoint& pregrasp,
                          const Eigen::Vector3d& v_end, const SplineReachOptions& options);

/// Options of the DMP reach (a discrete DMP per position coordinate, Ijspeert et al.).
struct DmpReachOptions {
  double duration = 2.0;            ///< s
  double sample_period = 1.0 / 60;  ///< s
  int basis_functions = 30;         ///< Gaussian kernels of the forcing term
  double alpha_z = 25.0;            ///< spring gain, 1/s (beta_z = alpha_z / 4: critical damping)
  double alpha_x = 2.0;             ///< canonical decay; the phase is exp(-2) at the end
  double integration_step = 1e-3;   ///< s, Euler step of the rollout

  bool IsValid(std::string* why) const;
};

/// A discrete DMP for 3D positions: learned from one demonstrated path, replayed toward a new
/// start and goal. The forcing term is scaled by the phase only (not by goal - start), so a
/// coordinate whose demonstrated start and goal coincide generalizes too.
class PositionDmp {
 public:
  /// Learns the forcing term from a demonstration (times strictly increasing, >= 3 samples,
  /// world positions in m) by locally weighted regression.
  PositionDmp(const std::vector<double>& times, const std::vector<Eigen::Vector3d>& positions,
              const DmpReachOptions& options);

  /// Positions at the sample times 0, period, ..., duration (duration = the options' one)
  /// from y0 to the goal g.
  std::vector<Eigen::Vector3d> Rollout(const Eigen::Vector3d& y0, const Eigen::Vector3d& g) const;

 private:
  Eigen::Vector3d Forcing(double x) const;

  DmpReachOptions options_;
  Eigen::VectorXd centres_, widths_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> weights_;
};

/// A reach by DMP: positions from `dmp` rolled out from the start to the pre-grasp position;
/// orientation (slerp) and fingers follow the DMP's progress along the path. The last sample
/// is the pre-grasp pose exactly.
CartesianPath DmpReach(const PositionDmp& dmp, const MotionWaypoint& start,
                       const MotionWaypoint& pregrasp, const DmpReachOptions& options);

/// Options of the lift that follows the grasp.
struct LiftOptions {
  double settle = 0.4;              ///< s, held at the grasp pose while the fingers close
  double height = 0.10;             ///< m, straight up
  double duration = 1.0;            ///< s, of the rise (minimum-jerk profile)
  double hold = 1.2;                ///< s, held at the top
  double sample_period = 1.0 / 60;  ///< s

  bool IsValid(std::string* why) const;
};

/// Settle, rise and hold after the grasp pose `grasp` (its time is the start): the wrist keeps
/// its orientation, the fingers their grasp values. The first sample is after grasp.t.
CartesianPath LiftPath(const MotionWaypoint& grasp, const LiftOptions& options);

}  // namespace graspsynth
