#include "simulation/trial.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"

namespace graspsynth {

bool TrialOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what, double v) {
    if (why) *why = std::string(what) + " = " + std::to_string(v);
    return false;
  };
  if (!(std::isfinite(time_step) && time_step >= 0.0 && time_step <= 0.02)) {
    return fail("time_step (s, 0 or up to 0.02)", time_step);
  }
  if (!(std::isfinite(hold) && hold >= 0.0)) return fail("hold (s)", hold);
  if (!TrialJudgeOptions::IsValid(why)) return false;
  if (!(std::isfinite(record_interval) && record_interval >= 0.0)) {
    return fail("record_interval (s)", record_interval);
  }
  return physics.IsValid(why);
}

double TrialOptions::step() const {
  if (time_step > 0.0) return time_step;
  return fidelity == Fidelity::kFull ? 0.001 : 0.004;
}

std::string TrialResult::BriefReport() const {
  std::ostringstream s;
  s << ToString(outcome) << ": " << reason << " (lift " << Format("%.4f", lift) << " m, "
    << statistics.dynamic_steps << " + " << statistics.kinematic_steps << " steps, "
    << Format("%.1f", cpu_time > 0 ? simulated_time / cpu_time : 0.0) << "x real time)";
  return s.str();
}

namespace {

// The world of a trial: the robot at the trajectory's first sample, the object at rest.
SimulationData MakeTrialWorld(const SimulationModel& model, const JointTrajectory& trajectory,
                              const TrialOptions& options) {
  WorldOptions world_options;
  world_options.time_step = options.step();
  world_options.arm_mode = options.fidelity == Fidelity::kFast   ? ArmMode::kKinematic
                           : options.fidelity == Fidelity::kFull ? ArmMode::kDynamic
                                                                 : ArmMode::kWristDynamic;
  world_options.theta = Radians(trajectory.theta_deg);
  world_options.object_xy = trajectory.object_xy;
  world_options.physics = options.physics;
  world_options.finger_mounts = options.finger_mounts;
  world_options.structured_solver = options.structured_solver;
  world_options.ode_broad_phase = options.ode_broad_phase;
  return SimulationData(model, world_options, trajectory.samples.front().arm,
                        trajectory.samples.front().hand);
}

// Plays the trajectory and the hold step by step, watching the trial; the verdict of an early
// end, or std::nullopt when it ran to its end (or to rest, kFast).
std::optional<TrialVerdict> PlayTrial(const SimulationModel& model,
                                      const JointTrajectory& trajectory,
                                      const TrialOptions& options, const StepObserver& observer,
                                      SimulationData* data, TrialWatch* watch,
                                      TrialResult* result) {
  const bool fast = options.fidelity != Fidelity::kFull;
  const double h = options.step();
  const double t_motion = trajectory.duration();
  const long steps = std::lround(result->planned_time / h);
  bool kinematic = fast;
  double next_record = 0.0;
  auto record = [&](double t) {
    if (options.record_interval <= 0.0 || t + 1e-9 < next_record) return;
    next_record += options.record_interval;
    result->states.push_back({t, data->arm_positions(), data->hand_positions(), data->object_pose(),
                              data->wrist_pose()});
  };
  record(0.0);

  for (long n = 0; n < steps; ++n) {
    const double t = n * h;
    const TrajectorySample now = SampleAt(trajectory, t);
    const TrajectorySample next = SampleAt(trajectory, t + h);
    data->SetArmCommand(ServoMode::kPosition, now.arm, (next.arm - now.arm) / h);
    data->SetHandCommand(ServoMode::kPosition, now.hand);
    try {
      StepTrialWorld(data, &kinematic);
    } catch (const OdeError& e) {
      return OdeFailureVerdict(data->time(), e.what());
    }
    if (observer) observer(*data);
    if (auto verdict = EarlyVerdict(*data, model.robot().arm, options)) return verdict;
    WatchStep(*data, options, watch);
    record(data->time());
    if (fast && AtRestForGood(*data, t_motion)) break;
  }
  return std::nullopt;
}

}  // namespace

void FinishTrial(const JudgedWorld& world, const HandModel& hand, const TrialWatch& watch,
                 double t_motion, const std::optional<TrialVerdict>& early,
                 const TrialJudgeOptions& options, TrialResult* result) {
  result->max_lift = watch.max_lift;
  result->max_penetration = watch.max_penetration;
  result->simulated_time = world.time();
  result->final_object_pose = world.object_pose();
  result->lift = result->final_object_pose.translation().z() - watch.X_WO_rest.translation().z();
  result->hold = MeasureHold(world, watch, hand);
  result->end_contacts = world.hand_object_contacts();
  const TrialVerdict verdict =
      early ? *early : JudgeTrial(world, watch, result->simulated_time - t_motion, options);
  result->outcome = verdict.outcome;
  result->reason = verdict.reason;
}

TrialResult RunTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                     const TrialOptions& options, const StepObserver& observer) {
  RequireValid(options, "invalid trial option");
  if (trajectory.samples.empty()) throw InputError("the trajectory has no samples");
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = ThreadCpuSeconds();
  SimulationData data = MakeTrialWorld(model, trajectory, options);

  TrialResult result;
  result.counts = data.counts();
  const Eigen::Isometry3d X_WO_rest = model.scene().ObjectPose(trajectory.placement());
  const double t_motion = trajectory.duration();
  result.planned_time = t_motion + options.hold;
  TrialWatch watch = StartTrialWatch(X_WO_rest);
  const std::optional<TrialVerdict> early =
      PlayTrial(model, trajectory, options, observer, &data, &watch, &result);

  FinishTrial(data, model.robot().hand, watch, t_motion, early, options, &result);
  result.statistics = data.statistics();
  result.wall_time = SecondsSince(wall_start);
  result.cpu_time = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace graspsynth
