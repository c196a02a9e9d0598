#include "motion/joint_space.hpp"

#include <cmath>

#include "common/demand.hpp"
#include "common/valid_options.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "motion/reach.hpp"

namespace graspsynth {
namespace {

double WrapAngle(double a) { return std::atan2(std::sin(a), std::cos(a)); }

// The arm angle to use: psi itself when feasible, else the point `margin` inside the nearest
// end of the nearest feasible arc (circular distance on [-pi, pi]).
std::optional<double> ChoosePsi(const std::vector<Interval>& feasible, double psi, double margin) {
  if (feasible.empty()) return std::nullopt;
  double best = 0.0;
  double best_distance = INFINITY;
  for (const Interval& iv : feasible) {
    if (iv.Contains(psi)) return psi;
    const double inset = std::min(margin, 0.5 * iv.width());
    for (const auto& [end, target] : {std::pair{iv.lo, iv.lo + inset}, {iv.hi, iv.hi - inset}}) {
      // an end at +-pi continues on the other side: the arc is not really bounded there.
      if (std::abs(std::abs(end) - M_PI) < 1e-12) continue;
      const double d = std::abs(WrapAngle(end - psi));
      if (d < best_distance) {
        best_distance = d;
        best = target;
      }
    }
  }
  if (!std::isfinite(best_distance)) return feasible.front().lo + 0.5 * feasible.front().width();
  return best;
}

}  // namespace

double WidestArmAngleWidth(const RobotModel& robot, const Eigen::Isometry3d& X_WH,
                           ArmBranch branch) {
  const Eigen::Isometry3d X_WF = X_WH * robot.X_FH.inverse();
  const ArmTargetForm form = PrepareArmTarget(robot.arm, X_WF, branch.gc4);
  if (form.status != IkStatus::kOk) return 0.0;
  const std::optional<Interval> widest =
      WidestInterval(FeasibleArmAngles(robot.arm, form, branch.gc2, branch.gc6));
  return widest ? widest->width() : 0.0;
}

bool JointSpaceOptions::IsValid(std::string* why) const {
  const auto fail = [why](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (!(psi_margin >= 0.0)) return fail("JointSpaceOptions::psi_margin must be >= 0");
  if (!(max_joint_step > 0.0)) return fail("JointSpaceOptions::max_joint_step must be positive");
  if (!(velocity_scale > 0.0 && velocity_scale <= 1.0)) {
    return fail("JointSpaceOptions::velocity_scale must be in (0, 1]");
  }
  return true;
}

std::optional<Vector7d> SolveWristPose(const RobotModel& robot, const Eigen::Isometry3d& X_WH,
                                       ArmBranch branch, double psi, const Vector7d& q_near,
                                       double margin) {
  const Eigen::Isometry3d X_WF = X_WH * robot.X_FH.inverse();
  const ArmTargetForm form = PrepareArmTarget(robot.arm, X_WF, branch.gc4);
  if (form.status != IkStatus::kOk) return std::nullopt;
  const std::vector<Interval> feasible = FeasibleArmAngles(robot.arm, form, branch.gc2, branch.gc6);
  const std::optional<double> chosen = ChoosePsi(feasible, psi, margin);
  if (!chosen) return std::nullopt;
  const Vector7d raw = JointsAtArmAngle(form, *chosen, branch.gc2, branch.gc6);
  return NearestEquivalent(robot.arm, raw, q_near);
}

JointSpaceResult ToJointTrajectory(const RobotModel& robot, const CartesianPath& path,
                                   const Vector7d& q_start, const JointSpaceOptions& options) {
  RequireValid(options, "invalid JointSpaceOptions");
  JointSpaceResult result;
  const ArmBranch branch = BranchOf(robot.arm, q_start);
  Vector7d q_prev = q_start;
  double psi = ArmAngleOf(robot.arm, q_start);
  double time_shift = 0.0;
  for (size_t k = 0; k < path.size(); ++k) {
    const MotionWaypoint& w = path[k];
    Eigen::Isometry3d X_WH = PoseFrom(w.p_WH, w.q_WH.normalized());
    const std::optional<Vector7d> q =
        SolveWristPose(robot, X_WH, branch, psi, q_prev, options.psi_margin);
    if (!q) {
      result.status = JointSpaceStatus::kUnreachable;
      result.failed_sample = static_cast<int>(k);
      result.message = "wrist pose " + std::to_string(k) + " (t = " + std::to_string(w.t) +
                       " s) has no solution within the joint limits on the start branch";
      return result;
    }
    const double step =
        k == 0 ? (*q - q_start).cwiseAbs().maxCoeff() : (*q - q_prev).cwiseAbs().maxCoeff();
    result.max_joint_step = std::max(result.max_joint_step, step);
    if (step > options.max_joint_step) {
      result.status = JointSpaceStatus::kJump;
      result.failed_sample = static_cast<int>(k);
      result.message = "a joint jumps by " + std::to_string(step) + " rad at wrist pose " +
                       std::to_string(k) + " (t = " + std::to_string(w.t) + " s)";
      return result;
    }
    TrajectorySample sample;
    sample.arm = *q;
    sample.hand = w.f;
    sample.t = w.t + time_shift;
    if (k > 0 && options.retime) {
      // the segment must last long enough for the slowest joint at its (scaled) cap.
      const TrajectorySample& prev = result.trajectory.samples.back();
      const double needed = std::max(((sample.arm - prev.arm).cwiseAbs().array() /
                                      (options.velocity_scale * robot.arm.max_velocity().array()))
                                         .maxCoeff(),
                                     ((sample.hand - prev.hand).cwiseAbs().array() /
                                      (options.velocity_scale * robot.hand.max_velocity().array()))
                                         .maxCoeff());
      const double dt = sample.t - prev.t;
      if (needed > dt) {
        time_shift += needed - dt;
        sample.t = prev.t + needed;
        result.added_time += needed - dt;
        ++result.retimed_segments;
      }
    }
    result.trajectory.samples.push_back(sample);
    psi = ArmAngleOf(robot.arm, *q);
    q_prev = *q;
  }
  result.status = JointSpaceStatus::kOk;
  return result;
}

bool JointReachOptions::IsValid(std::string* why) const {
  const auto fail = [why](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (!(min_duration > 0.0)) return fail("JointReachOptions::min_duration must be positive");
  if (!(sample_period > 0.0)) return fail("JointReachOptions::sample_period must be positive");
  if (!(velocity_scale > 0.0 && velocity_scale <= 1.0)) {
    return fail("JointReachOptions::velocity_scale must be in (0, 1]");
  }
  return true;
}

std::vector<TrajectorySample> JointReach(const RobotModel& robot, const Vector7d& q_start,
                                         const HandVector& f_start, const Vector7d& q_goal,
                                         const HandVector& f_goal,
                                         const JointReachOptions& options) {
  RequireValid(options, "invalid JointReachOptions");
  constexpr double kPeakSlope = 1.875;  // of the minimum-jerk profile
  const double arm_time = ((q_goal - q_start).cwiseAbs().array() /
                           (options.velocity_scale * robot.arm.max_velocity().array()))
                              .maxCoeff();
  const double hand_time = ((f_goal - f_start).cwiseAbs().array() /
                            (options.velocity_scale * robot.hand.max_velocity().array()))
                               .maxCoeff();
  const double duration =
      std::max(options.min_duration, kPeakSlope * std::max(arm_time, hand_time));
  const int n = std::max(1, static_cast<int>(std::ceil(duration / options.sample_period - 1e-9)));
  std::vector<TrajectorySample> samples(static_cast<size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    TrajectorySample& s = samples[static_cast<size_t>(k)];
    s.t = std::min(k * options.sample_period, duration);
    const double u = MinimumJerk(s.t / duration);
    s.arm = q_start + u * (q_goal - q_start);
    s.hand = f_start + u * (f_goal - f_start);
  }
  samples.back().arm = q_goal;
  samples.back().hand = f_goal;
  return samples;
}

}  // namespace graspsynth
