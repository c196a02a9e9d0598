#include "solver/reach_planning.hpp"

#include <optional>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"

namespace graspsynth {

namespace {

// True when the robot at (q, f) touches the table or the object at its rest pose.
bool InCollision(const SynthesisModel& model, const Vector7d& q, const HandVector& f,
                 const Eigen::Isometry3d& X_WO, CollisionData* data) {
  SetState(model.collision(), q, f, X_WO, data);
  CollideOptions co;
  co.max_pairs = 1;
  return Collide(model.collision(), GroupSet::Robot(), GroupSet::World(), data, co).collision();
}

// A reach followed by `tail` (grasping motion and lift, times from the pre-grasp) as one
// Cartesian path and its joint trajectory.
struct ReachAttempt {
  ReachMethod method = ReachMethod::kSpline;
  CartesianPath path;
  size_t reach_samples = 0;  // path samples of the reach, pre-grasp included
  JointSpaceResult joints;
  int margin_failed_sample = -1;  // spline: the first reach pose that fails the margin test

  bool ok() const { return joints.status == JointSpaceStatus::kOk; }
  // spline: playable, and every reach pose survives the margin test.
  bool margin_ok() const { return ok() && margin_failed_sample < 0; }
};

// `tail` shifted to start at `t0`, its first sample (the pre-grasp) left out.
void AppendTail(const CartesianPath& tail, double t0, CartesianPath* path) {
  for (size_t i = 1; i < tail.size(); ++i) {
    MotionWaypoint w = tail[i];
    w.t += t0;
    path->push_back(w);
  }
}

// The first reach pose (index) that has no feasible arm angle on `branch` once the wrist moves
// by +-margin along a world axis, or -1.
int FirstPoseWithoutMargin(const RobotModel& robot, const CartesianPath& path, size_t count,
                           ArmBranch branch, double margin) {
  for (size_t i = 0; i < count; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {-1.0, 1.0}) {
        Eigen::Isometry3d X = WaypointPose(path[i]);
        X.translation()[axis] += sign * margin;
        if (WidestArmAngleWidth(robot, X, branch) <= 0.0) return static_cast<int>(i);
      }
    }
  }
  return -1;
}

ReachAttempt SplineReachAttempt(const RobotModel& robot, const GraspingMotion& motion,
                                const CartesianPath& tail, const Vector7d& q_start,
                                double theta_deg, const ReachPlanOptions& options) {
  ReachAttempt a;
  a.method = ReachMethod::kSpline;
  MotionWaypoint start;
  const Eigen::Isometry3d X_start = ArmFlangePose(robot.arm, q_start) * robot.X_FH;
  start.p_WH = X_start.translation();
  start.q_WH = Eigen::Quaterniond(X_start.linear()).normalized();
  start.f = motion.pregrasp().f;
  const MotionWaypoint& w0 = motion.waypoints[0];
  const MotionWaypoint& w1 = motion.waypoints[1];
  const Eigen::Vector3d v_end = (w1.p_WH - w0.p_WH) / std::max(1e-6, w1.t - w0.t);
  a.path = SplineReach(start, motion.pregrasp(), v_end, options.spline);
  a.reach_samples = a.path.size();
  AppendTail(tail, a.path.back().t, &a.path);
  a.joints = ToJointTrajectory(robot, a.path, q_start, options.joint_space);
  a.joints.trajectory.theta_deg = theta_deg;
  if (a.ok()) {
    a.margin_failed_sample = FirstPoseWithoutMargin(robot, a.path, a.reach_samples,
                                                    BranchOf(robot.arm, q_start), options.margin);
  }
  return a;
}

// The joint reach: the grasping motion and lift played from the pre-grasp configuration on the
// start's branch, or the first other branch (the wrist flip first) that plays them, and a
// collision-free minimum-jerk move to it. std::nullopt, with the reason in `why`, when no
// branch works; on success `why` names the branch.
std::optional<ReachAttempt> JointReachAttempt(const SynthesisModel& model,
                                              const GraspingMotion& motion,
                                              const CartesianPath& tail, const Vector7d& q_start,
                                              const SynthesisTask& task,
                                              const ReachPlanOptions& options, CollisionData* data,
                                              std::string* why) {
  const RobotModel& robot = model.robot();
  const int start_branch = BranchOf(robot.arm, q_start).index();
  const double psi = ArmAngleOf(robot.arm, q_start);
  std::ostringstream failures;
  std::vector<int> order = {start_branch};
  for (int index : kBranchPreference) {
    if (index != start_branch) order.push_back(index);
  }
  for (int index : order) {
    const std::optional<Vector7d> q_pre =
        SolveWristPose(robot, WaypointPose(motion.pregrasp()), ArmBranch::FromIndex(index), psi,
                       q_start, options.joint_space.psi_margin);
    if (!q_pre) continue;
    JointSpaceResult after = ToJointTrajectory(robot, tail, *q_pre, options.joint_space);
    if (after.status != JointSpaceStatus::kOk) continue;
    const std::vector<TrajectorySample> reach =
        JointReach(robot, q_start, motion.pregrasp().f, *q_pre, motion.pregrasp().f, options.joint);
    int hit = -1;
    for (size_t k = 0; k < reach.size() && hit < 0; ++k) {
      if (InCollision(model, reach[k].arm, reach[k].hand, task.X_WO, data))
        hit = static_cast<int>(k);
    }
    if (hit >= 0) {
      failures << " branch " << index << ": the move collides at t = " << reach[hit].t << " s;";
      continue;
    }
    ReachAttempt a;
    a.method = ReachMethod::kJoint;
    for (const TrajectorySample& s : reach) {
      const Eigen::Isometry3d X = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
      MotionWaypoint w;
      w.t = s.t;
      w.p_WH = X.translation();
      w.q_WH = Eigen::Quaterniond(X.linear()).normalized();
      w.f = s.hand;
      a.path.push_back(w);
    }
    a.path.back() = tail.front();
    a.path.back().t = reach.back().t;
    a.reach_samples = a.path.size();
    AppendTail(tail, reach.back().t, &a.path);
    a.joints = std::move(after);
    a.joints.trajectory.theta_deg = task.theta_deg;
    a.joints.trajectory.samples.erase(a.joints.trajectory.samples.begin());
    for (TrajectorySample& s : a.joints.trajectory.samples) s.t += reach.back().t;
    a.joints.trajectory.samples.insert(a.joints.trajectory.samples.begin(), reach.begin(),
                                       reach.end());
    for (size_t k = 1; k < reach.size(); ++k) {
      a.joints.max_joint_step = std::max(a.joints.max_joint_step,
                                         (reach[k].arm - reach[k - 1].arm).cwiseAbs().maxCoeff());
    }
    std::ostringstream s;
    s << " on branch " << index << " (" << reach.back().t << " s)";
    *why = s.str();
    return a;
  }
  *why = "no branch plays the grasping motion from a collision-free joint move;" + failures.str();
  return std::nullopt;
}

// `r` with the reach `chosen`.
ReachPlanResult Chosen(ReachAttempt chosen, ReachPlanResult r) {
  r.chosen = true;
  r.used = chosen.method;
  r.path = std::move(chosen.path);
  r.reach_samples = chosen.reach_samples;
  r.joints = std::move(chosen.joints);
  return r;
}

// The spline reach, with the default rest pose on another branch when it cannot be played.
ReachPlanResult PlanSplineReach(const SynthesisModel& model, const SynthesisTask& task,
                                const GraspingMotion& motion, const CartesianPath& tail,
                                const ReachAttempt& spline, const ReachPlanOptions& options,
                                ReachPlanResult r, CollisionData* data) {
  const RobotModel& robot = model.robot();
  std::ostringstream why;
  std::optional<ReachAttempt> chosen = spline;
  why << "spline reach requested";
  if (!spline.ok() && !options.start_given) {
    // the default rest pose on another branch (the wrist flip first), as ReplayDemoLog does:
    // a hand turned far from the rest orientation can need it. A start given by the user is
    // kept.
    const Eigen::Isometry3d X_rest_flange = ArmFlangePose(robot.arm, r.start);
    for (int index : {4, 1, 5, 2, 6, 3, 7}) {
      const std::optional<MidArcSolution> other =
          SolveArmIkMidArc(robot.arm, X_rest_flange, ArmBranch::FromIndex(index));
      if (!other || InCollision(model, other->q, motion.pregrasp().f, task.X_WO, data)) continue;
      ReachAttempt a = SplineReachAttempt(robot, motion, tail, other->q, task.theta_deg, options);
      if (a.ok()) {
        r.start = other->q;
        chosen = std::move(a);
        why << "; the rest pose on branch " << index << " (the elbow-up one cannot play it)";
        break;
      }
    }
  }
  r.reason = why.str();
  return Chosen(std::move(*chosen), std::move(r));
}

}  // namespace

const char* ToString(ReachMethod method) {
  switch (method) {
    case ReachMethod::kSpline:
      return "spline";
    case ReachMethod::kJoint:
      return "joint";
    case ReachMethod::kAuto:
      return "auto";
  }
  return "?";
}

ReachMethod ParseReachMethod(const std::string& text) {
  if (text == "spline") return ReachMethod::kSpline;
  if (text == "joint") return ReachMethod::kJoint;
  if (text == "auto") return ReachMethod::kAuto;
  throw InputError("unknown reach method '" + text + "' (spline, joint or auto)");
}

ReachPlanResult PlanReach(const SynthesisModel& model, const SynthesisTask& task,
                          const GraspingMotion& motion, const CartesianPath& tail,
                          const Vector7d& q_start, const ReachPlanOptions& options,
                          CollisionData* data) {
  ReachPlanResult r;
  r.start = q_start;
  const ReachAttempt spline =
      options.method == ReachMethod::kJoint
          ? ReachAttempt{}
          : SplineReachAttempt(model.robot(), motion, tail, q_start, task.theta_deg, options);
  if (options.method == ReachMethod::kSpline) {
    return PlanSplineReach(model, task, motion, tail, spline, options, std::move(r), data);
  }
  std::ostringstream why;
  std::optional<ReachAttempt> chosen;
  if (options.method == ReachMethod::kAuto) {
    if (spline.margin_ok()) {
      chosen = spline;
      why << "spline reach (reachable with " << options.margin * 1000.0 << " mm to spare)";
    } else if (spline.ok()) {
      why << "the spline reach passes within " << options.margin * 1000.0
          << " mm of the workspace's edge at wrist pose " << spline.margin_failed_sample;
    } else {
      why << "the spline reach cannot be played: " << spline.joints.message;
    }
  } else {
    why << "joint reach requested";
  }
  if (!chosen) {
    std::string joint_why;
    std::optional<ReachAttempt> joint =
        JointReachAttempt(model, motion, tail, q_start, task, options, data, &joint_why);
    if (joint) {
      chosen = std::move(joint);
      why << "; joint reach" << joint_why;
    } else {
      why << "; the joint reach failed too: " << joint_why;
      if (spline.ok()) {
        chosen = spline;
        why << "; kept the spline reach";
      }
    }
  }
  r.reason = why.str();
  if (!chosen) return r;
  return Chosen(std::move(*chosen), std::move(r));
}

}  // namespace graspsynth
