#include "learning_data/demo_replay.hpp"
#include "kinematics/pose_math.hpp"

#include <optional>
#include <sstream>
#include <vector>

namespace graspsynth {

DemoReplay ReplayDemoLog(const RobotModel& robot, const DemoLog& log,
                         const JointSpaceOptions& options) {
  DemoReplay replay;
  if (log.samples.size() < 2) {
    replay.message = log.source + ": a replay needs at least two samples";
    return replay;
  }
  CartesianPath path;
  path.reserve(log.samples.size());
  for (const DemoSample& s : log.samples) {
    MotionWaypoint w;
    w.t = s.t;
    w.p_WH = s.p_WH;
    w.q_WH = s.q_WH.normalized();
    w.f = s.f;
    path.push_back(w);
  }
  Eigen::Isometry3d X_WH0 = PoseFrom(path.front().p_WH, path.front().q_WH);
  const Eigen::Isometry3d X_WF0 = X_WH0 * robot.X_FH.inverse();
  // the elbow-up branch first, then its wrist flip, then the others; the first branch on
  // which the whole log converts is used.
  std::optional<MidArcSolution> start;
  JointSpaceResult joints;
  std::string first_failure;
  for (int index : kBranchPreference) {
    const std::optional<MidArcSolution> s =
        SolveArmIkMidArc(robot.arm, X_WF0, ArmBranch::FromIndex(index));
    if (!s) continue;
    JointSpaceResult j = ToJointTrajectory(robot, path, s->q, options);
    j.trajectory.theta_deg = log.metadata.theta_deg;
    j.trajectory.object_xy = Eigen::Vector2d(log.metadata.object_position.head<2>());
    if (j.status == JointSpaceStatus::kOk) {
      start = s;
      joints = std::move(j);
      break;
    }
    if (first_failure.empty()) {
      std::ostringstream why;
      why << log.source << ": sample " << j.failed_sample + 1
          << " (t = " << log.samples[std::max(j.failed_sample, 0)].t << " s): " << j.message;
      first_failure = why.str();
    }
  }
  if (!start) {
    replay.message = first_failure.empty()
                         ? log.source + ": the first wrist pose (line of sample 1) is not reachable"
                         : first_failure;
    return replay;
  }
  replay.trajectory = joints.trajectory;
  replay.trajectory.samples.front().arm = start->q;
  const std::optional<size_t> grasp = FindEvent(log, DemoEvent::kGrasp);
  std::vector<size_t> marks = {0};
  if (grasp) marks.push_back(*grasp);
  marks.push_back(log.samples.size() - 1);
  for (size_t i : marks) {
    WristWaypoint w;
    w.t = replay.trajectory.samples[i].t;
    w.p_WH = path[i].p_WH;
    w.q_WH = path[i].q_WH;
    replay.trajectory.waypoints.push_back(w);
  }
  replay.ok = true;
  return replay;
}

}  // namespace graspsynth
