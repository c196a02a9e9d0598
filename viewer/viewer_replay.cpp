#include "viewer/viewer_replay.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>

#include "common/demand.hpp"
#include "common/format.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "motion/joint_space.hpp"

namespace graspsynth::viewer {
namespace {

// the first branch on which X_WH has a solution, at the middle of its widest feasible arc.
std::optional<Vector7d> RestConfiguration(const RobotModel& robot, const Eigen::Isometry3d& X_WH) {
  const auto s = SolveArmIkMidArc(robot.arm, X_WH * robot.X_FH.inverse());
  if (!s) return std::nullopt;
  return s->q;
}

// The index of the last sample at or before t (t within the samples' span).
size_t SampleIndexAt(const std::vector<TrajectorySample>& samples, double t) {
  return std::upper_bound(
             samples.begin() + 1, samples.end(), t,
             [](double time, const TrajectorySample& sample) { return time < sample.t; }) -
         samples.begin() - 1;
}

// `state` (joints set) with a trial's object pose, contacts and outcome at t.
ViewerState TrialStateAt(const ViewerReplay& replay, double t, ViewerState state) {
  const std::vector<TrajectorySample>& samples = replay.trajectory.samples;
  const size_t i = SampleIndexAt(samples, t);
  const size_t j = std::min(i + 1, samples.size() - 1);
  const double span = samples[j].t - samples[i].t;
  const double a = span > 0.0 ? (t - samples[i].t) / span : 0.0;
  const Eigen::Quaterniond q = Eigen::Quaterniond(replay.X_WO[i].linear())
                                   .slerp(a, Eigen::Quaterniond(replay.X_WO[j].linear()));
  state.X_WO =
      PoseFrom((1.0 - a) * replay.X_WO[i].translation() + a * replay.X_WO[j].translation(), q);
  state.contacts = replay.contacts[i];
  if (i + 1 == samples.size()) state.outcome = replay.outcome;
  return state;
}

}  // namespace

ViewerReplay ReplayOfTrajectory(JointTrajectory trajectory, const std::string& source) {
  GS_DEMAND(!trajectory.samples.empty(), "a replay needs at least one sample");
  ViewerReplay replay;
  replay.label = "trajectory " + source + " | " + Format("theta %.1f deg", trajectory.theta_deg);
  if (trajectory.object_xy) {
    std::ostringstream at;
    at.setf(std::ios::fixed);
    at.precision(3);
    at << " at (" << trajectory.object_xy->x() << ", " << trajectory.object_xy->y() << ") m";
    replay.label += at.str();
  }
  replay.trajectory = std::move(trajectory);
  return replay;
}

ViewerReplay ReplayOfLog(const RobotModel& robot, const DemoLog& log) {
  GS_DEMAND(!log.samples.empty(), "a replay needs at least one sample");
  ViewerReplay replay;
  replay.label = "log " + log.source + " | " + Format("theta %.1f deg", log.metadata.theta_deg);
  replay.trajectory.theta_deg = log.metadata.theta_deg;
  std::optional<Vector7d> q;
  std::optional<size_t> first_reached;
  for (const DemoSample& s : log.samples) {
    Eigen::Isometry3d X_WH = PoseFrom(s.p_WH, s.q_WH.normalized());
    const std::optional<Vector7d> next =
        q ? SolveWristPose(robot, X_WH, BranchOf(robot.arm, *q), ArmAngleOf(robot.arm, *q), *q)
          : RestConfiguration(robot, X_WH);
    if (next) {
      q = next;
      if (!first_reached) first_reached = replay.trajectory.samples.size();
    } else {
      ++replay.unreached;
    }
    replay.reached.push_back(next.has_value());
    TrajectorySample sample;
    sample.t = s.t;
    sample.arm = q.value_or(Vector7d::Zero());
    sample.hand = s.f;
    replay.trajectory.samples.push_back(sample);
    replay.p_WO.push_back(s.p_WO);
    replay.events.push_back(s.event);
  }
  // the samples before the first reached pose take its configuration.
  if (first_reached) {
    for (size_t k = 0; k < *first_reached; ++k) {
      replay.trajectory.samples[k].arm = replay.trajectory.samples[*first_reached].arm;
    }
  }
  return replay;
}

ViewerReplay ReplayOfTrial(const TrialRecord& record, const std::string& source) {
  GS_DEMAND(!record.frames.empty(), "a replay needs at least one frame");
  ViewerReplay replay;
  replay.label =
      "trial " + source + " | " + Format("theta %.1f deg", record.theta_deg) + " | as simulated";
  replay.trajectory.theta_deg = record.theta_deg;
  replay.trajectory.object_xy = record.object_xy;
  for (const TrialRecordFrame& frame : record.frames) {
    replay.trajectory.samples.push_back({frame.t, frame.arm, frame.hand});
    replay.X_WO.push_back(PoseFrom(frame.p_WO, frame.q_WO));
    std::vector<Eigen::Vector3d> points;
    for (const RecordedContact& c : frame.contacts) points.push_back(c.p_WC);
    replay.contacts.push_back(std::move(points));
  }
  ViewerOutcome outcome;
  outcome.success = record.success();
  outcome.text = record.success()
                     ? "success: " + record.reason
                     : "FAILED (" + std::string(ToString(record.outcome)) + "): " + record.reason;
  replay.outcome = outcome;
  return replay;
}

ViewerReplay RestReplay() {
  ViewerReplay replay;
  replay.label = "robot at rest";
  replay.trajectory.samples.push_back(TrajectorySample{});
  return replay;
}

ViewerState ReplayStateAt(const ViewerReplay& replay, const SceneModel& scene, double t) {
  const std::vector<TrajectorySample>& samples = replay.trajectory.samples;
  t = std::clamp(t, replay.start_time(), replay.end_time());
  const TrajectorySample s = SampleAt(replay.trajectory, t);
  ViewerState state;
  state.t = t;
  state.arm = s.arm;
  state.hand = s.hand;
  state.X_WO = scene.ObjectPose(replay.trajectory.placement());
  state.text = replay.label;
  if (!replay.X_WO.empty()) return TrialStateAt(replay, t, state);
  if (replay.p_WO.empty()) return state;

  // i: the last sample at or before t; the object linear from it to the next.
  const size_t i = SampleIndexAt(samples, t);
  const size_t j = std::min(i + 1, samples.size() - 1);
  const double span = samples[j].t - samples[i].t;
  const double a = span > 0.0 ? (t - samples[i].t) / span : 0.0;
  state.X_WO.translation() = (1.0 - a) * replay.p_WO[i] + a * replay.p_WO[j];
  for (size_t k = i + 1; k-- > 0;) {
    if (replay.events[k] == DemoEvent::kGrasp) {
      state.text += " | grasp";
      break;
    }
    if (replay.events[k] == DemoEvent::kEnd) {
      state.text += " | end of trial";
      break;
    }
  }
  if (!replay.reached[i]) state.text += " | wrist pose out of reach: holding";
  return state;
}

}  // namespace graspsynth::viewer
