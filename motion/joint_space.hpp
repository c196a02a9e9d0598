#pragma once

/// @file
/// From a Cartesian wrist-and-finger path to the robot's joint trajectory, through the analytic
/// IK with a continuous arm angle: the branch of the start configuration is kept, the arm angle
/// stays where it is while it remains feasible and otherwise moves to the nearest feasible arc,
/// joints beyond +-180 deg take the 2 pi-equivalent nearest the previous sample, and segments
/// are stretched in time where a joint would exceed its velocity cap.

#include <string>

#include <optional>

#include "kinematics/arm_ik.hpp"
#include "kinematics/robot_description.hpp"
#include "motion/joint_trajectory.hpp"
#include "motion/reach.hpp"

namespace graspsynth {

/// Options of ToJointTrajectory.
struct JointSpaceOptions {
  /// When the arm angle has to move into a feasible arc, it goes this far inside it (rad), or
  /// to the arc's middle when the arc is narrower than twice this.
  double psi_margin = Radians(5.0);
  /// A joint step larger than this between consecutive samples (rad) is a jump: a failure.
  double max_joint_step = 0.35;
  /// Stretch segments so that no arm or hand joint exceeds velocity_scale times its cap.
  bool retime = true;
  double velocity_scale = 0.9;  ///< fraction of the velocity caps used by the re-timing, (0, 1]

  bool IsValid(std::string* why) const;
};

/// Outcome of the conversion.
enum class JointSpaceStatus {
  kOk,
  kUnreachable,  ///< a wrist pose has no solution on the branch within the joint limits
  kJump,         ///< consecutive samples need a joint step above max_joint_step
};

/// The joint trajectory and what it took to make it.
struct JointSpaceResult {
  JointSpaceStatus status = JointSpaceStatus::kUnreachable;
  std::string message;          ///< why, when status is not kOk
  int failed_sample = -1;       ///< index into the path of the first failing sample
  JointTrajectory trajectory;   ///< the samples converted so far (all of them when kOk)
  double max_joint_step = 0.0;  ///< largest arm joint step between samples, rad
  double added_time = 0.0;      ///< s added by the re-timing
  int retimed_segments = 0;     ///< segments stretched by the re-timing
};

/// Converts `path` (times strictly increasing; wrist = hand-mount frame H) into joint samples
/// starting from the arm configuration q_start, whose branch is kept. The first sample's time
/// is kept; later times grow by the re-timing. The conversion knows nothing of the object: the
/// trajectory's theta_deg is left at 0 for the caller, who knows the task, to set.
JointSpaceResult ToJointTrajectory(const RobotModel& robot, const CartesianPath& path,
                                   const Vector7d& q_start, const JointSpaceOptions& options = {});

/// Options of the joint-space reach.
struct JointReachOptions {
  double min_duration = 2.0;        ///< s, the shortest reach
  double sample_period = 1.0 / 60;  ///< s, spacing of the samples
  /// The duration grows until no arm or hand joint exceeds this fraction of its velocity cap,
  /// (0, 1].
  double velocity_scale = 0.9;

  bool IsValid(std::string* why) const;
};

/// A reach in joint space: every arm and hand joint from (q_start, f_start) to (q_goal,
/// f_goal) on the same minimum-jerk profile, so the arm never leaves the box of its joint
/// limits and changes branch only where the two ends differ. The duration is min_duration or
/// longer, so that each joint's peak speed (1.875 x its change / duration) stays within
/// velocity_scale of its cap. Samples from t = 0 to the duration; the first is the start and
/// the last the goal exactly. Aborts (GS_DEMAND) on invalid options.
std::vector<TrajectorySample> JointReach(const RobotModel& robot, const Vector7d& q_start,
                                         const HandVector& f_start, const Vector7d& q_goal,
                                         const HandVector& f_goal,
                                         const JointReachOptions& options = {});

/// The arm configuration for wrist pose X_WH on `branch` with the arm angle nearest `psi`
/// (kept when feasible, else moved into the nearest feasible arc by `margin`), 2 pi-equivalents
/// nearest q_near. std::nullopt when the pose has no feasible arm angle on that branch.
std::optional<Vector7d> SolveWristPose(const RobotModel& robot, const Eigen::Isometry3d& X_WH,
                                       ArmBranch branch, double psi, const Vector7d& q_near,
                                       double margin = Radians(5.0));

/// The width of the widest feasible arm-angle arc of wrist pose X_WH (hand mount H in world)
/// on `branch`, rad; 0 when the pose has none (outside the workspace or every arm angle beyond
/// a joint limit).
double WidestArmAngleWidth(const RobotModel& robot, const Eigen::Isometry3d& X_WH,
                           ArmBranch branch);

}  // namespace graspsynth
