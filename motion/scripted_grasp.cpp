#include "motion/scripted_grasp.hpp"

#include <cmath>

#include "common/errors.hpp"
#include "common/valid_options.hpp"
#include "kinematics/arm_ik.hpp"
#include "motion/joint_space.hpp"
#include "motion/reach.hpp"
#include "scene/base_frame.hpp"

namespace graspsynth {
namespace {

Eigen::Isometry3d Pose(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

MotionWaypoint Waypoint(double t, const Eigen::Isometry3d& X, const HandVector& f) {
  MotionWaypoint w;
  w.t = t;
  w.p_WH = X.translation();
  w.q_WH = Eigen::Quaterniond(X.linear()).normalized();
  w.f = f;
  return w;
}

// Appends samples (t0, t0 + duration] moving from a to b (min-jerk, slerp, finger blend).
void AppendSegment(CartesianPath* path, const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
                   const HandVector& fa, const HandVector& fb, double duration, double period) {
  const double t0 = path->back().t;
  const int n = std::max(1, static_cast<int>(std::ceil(duration / period - 1e-9)));
  const Eigen::Quaterniond qa(a.linear()), qb(b.linear());
  for (int k = 1; k <= n; ++k) {
    const double s = MinimumJerk(static_cast<double>(k) / n);
    Eigen::Isometry3d X =
        Pose(qa.slerp(s, qb).toRotationMatrix(), (1.0 - s) * a.translation() + s * b.translation());
    path->push_back(Waypoint(t0 + duration * k / n, X, (1.0 - s) * fa + s * fb));
  }
}

}  // namespace

bool ScriptedGraspOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!std::isfinite(theta_deg)) return fail("theta_deg is not finite");
  if (!positive(grasp_radius)) return fail("grasp_radius must be positive");
  if (bar_in_hand && !bar_in_hand->allFinite()) return fail("bar_in_hand is not finite");
  if (!std::isfinite(yaw)) return fail("yaw is not finite");
  if (side != 1 && side != -1) return fail("side must be +1 or -1");
  if (!std::isfinite(pregrasp_up) || !std::isfinite(pregrasp_back)) {
    return fail("the pre-grasp offsets must be finite");
  }
  if ((open && !open->allFinite()) || (closed && !closed->allFinite())) {
    return fail("the finger shapes must be finite");
  }
  for (double d : {reach_duration, approach_duration, close_duration, settle_duration,
                   lift_duration, end_duration, sample_period}) {
    if (!positive(d)) return fail("every duration and the sample period must be positive");
  }
  if (!std::isfinite(lift_height)) return fail("lift_height is not finite");
  return true;
}

namespace {

// the wrist pose X_WH of the grasp in the scene's frame, with the handle at `bar_in_hand` of H.
Eigen::Isometry3d GraspWristPose(const SceneModel& scene, const ScriptedGraspOptions& options,
                                 const Eigen::Vector3d& bar_in_hand);

}  // namespace

RobotGrasp ScriptedGraspShapes(const RobotModel& robot, const ScriptedGraspOptions& options) {
  RobotGrasp g =
      options.open && options.closed && options.bar_in_hand ? RobotGrasp{} : RobotGraspOf(robot);
  if (options.open) g.open = *options.open;
  if (options.closed) g.closed = *options.closed;
  if (options.bar_in_hand) g.bar_in_hand = *options.bar_in_hand;
  if (options.keep_open) g.closed = g.open;
  return g;
}

Eigen::Isometry3d GraspWristPose(const RobotModel& robot, const SceneModel& scene_in,
                                 const ScriptedGraspOptions& options) {
  const SceneModel scene = SceneInBaseFrame(scene_in, robot.X_WB);
  return GraspWristPose(scene, options, ScriptedGraspShapes(robot, options).bar_in_hand);
}

namespace {

Eigen::Isometry3d GraspWristPose(const SceneModel& scene, const ScriptedGraspOptions& options,
                                 const Eigen::Vector3d& bar_in_hand) {
  const Eigen::Isometry3d X_WO = scene.ObjectPose(options.theta_deg * kDeg);
  const Eigen::Vector3d h = scene.object.HandleDirection(X_WO);  // along the handle, horizontal
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  // z_H across the handle (from the wrist's side toward it), x_H down, y_H = z_H x x_H.
  const Eigen::Vector3d across = options.side * up.cross(h);
  const Eigen::Vector3d z_H = Eigen::AngleAxisd(options.yaw, up) * across;
  Eigen::Matrix3d R;
  R.col(0) = -up;
  R.col(2) = z_H;
  R.col(1) = z_H.cross(-up);
  const ObjectModel& o = scene.object;
  const Eigen::Vector3d p_bar = X_WO.translation() + options.grasp_radius * h +
                                (o.Handle("the scripted grasp").axis_height - o.rest_height) * up;
  return Pose(R, p_bar - R * bar_in_hand);
}

}  // namespace

ScriptedGraspResult BuildScriptedGrasp(const RobotModel& robot, const SceneModel& scene_in,
                                       const ScriptedGraspOptions& options) {
  RequireValid(options, "invalid scripted grasp option");
  const SceneModel scene = SceneInBaseFrame(scene_in, robot.X_WB);
  const RobotGrasp shapes = ScriptedGraspShapes(robot, options);
  const HandVector& open = shapes.open;
  const HandVector& closed = shapes.closed;
  ScriptedGraspResult result;
  const Eigen::Isometry3d X_grasp = GraspWristPose(scene, options, shapes.bar_in_hand);
  const Vector7d rest =
      options.rest ? *options.rest : DefaultRestConfiguration(robot, scene, X_grasp.linear());
  const Eigen::Isometry3d X_rest = ArmFlangePose(robot.arm, rest) * robot.X_FH;
  Eigen::Isometry3d X_pre = X_grasp;
  X_pre.translation() += options.pregrasp_up * Eigen::Vector3d::UnitZ() -
                         options.pregrasp_back * X_grasp.linear().col(2);
  Eigen::Isometry3d X_lift = X_grasp;
  X_lift.translation().z() += options.lift_height;
  result.X_WH_grasp = X_grasp;
  result.X_WH_pregrasp = X_pre;

  const double dt = options.sample_period;
  CartesianPath path = {Waypoint(0.0, X_rest, open)};
  AppendSegment(&path, X_rest, X_pre, open, open, options.reach_duration, dt);
  const size_t i_pre = path.size() - 1;
  AppendSegment(&path, X_pre, X_grasp, open, open, options.approach_duration, dt);
  const size_t i_grasp = path.size() - 1;
  AppendSegment(&path, X_grasp, X_grasp, open, closed, options.close_duration, dt);
  const size_t i_closed = path.size() - 1;
  AppendSegment(&path, X_grasp, X_grasp, closed, closed, options.settle_duration, dt);
  AppendSegment(&path, X_grasp, X_lift, closed, closed, options.lift_duration, dt);
  const size_t i_lift = path.size() - 1;
  AppendSegment(&path, X_lift, X_lift, closed, closed, options.end_duration, dt);

  JointSpaceOptions js;
  const JointSpaceResult joints = ToJointTrajectory(robot, path, rest, js);
  if (joints.status != JointSpaceStatus::kOk) {
    result.message = joints.message;
    return result;
  }
  result.trajectory = joints.trajectory;
  result.trajectory.theta_deg = options.theta_deg;
  // the controller starts exactly at the rest configuration.
  result.trajectory.samples.front().arm = rest;
  const Eigen::Isometry3d poses[] = {X_rest, X_pre, X_grasp, X_grasp, X_lift};
  const size_t index[] = {0, i_pre, i_grasp, i_closed, i_lift};
  for (int k = 0; k < 5; ++k) {
    WristWaypoint w;
    w.t = result.trajectory.samples[index[k]].t;
    w.p_WH = poses[k].translation();
    w.q_WH = Eigen::Quaterniond(poses[k].linear()).normalized();
    result.trajectory.waypoints.push_back(w);
  }
  result.ok = true;
  return result;
}

}  // namespace graspsynth
