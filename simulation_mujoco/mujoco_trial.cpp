#include "simulation_mujoco/mujoco_trial.hpp"

#include <time.h>

#include <cmath>
#include <optional>
#include <stdexcept>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "simulation/trial_judge.hpp"
#include "simulation_mujoco/mujoco_world.hpp"

namespace graspsynth {
namespace {

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// as the fast ODE trial (simulation/trial.cpp): once the robot holds still and the object lies
// on the table untouched, nothing can change any more.
bool AtRestForGood(const MujocoData& data, double t_motion) {
  const ContactReport& c = data.contacts();
  return data.time() > t_motion + 0.1 && c.object_table > 0 && c.object_hand == 0 &&
         c.object_arm == 0 && data.object_velocity().norm() < 1e-3 &&
         data.object_angular_velocity().norm() < 1e-2;
}

// Plays the trajectory and the hold step by step, watching the trial; the verdict of an early
// end, or std::nullopt when it ran to its end (or to rest).
std::optional<TrialVerdict> PlayTrial(const SimulationModel& model,
                                      const JointTrajectory& trajectory, const TrialOptions& trial,
                                      double h, MujocoData* data, TrialWatch* watch,
                                      TrialResult* result) {
  const double t_motion = trajectory.duration();
  const long steps = std::lround(result->planned_time / h);
  double next_record = 0.0;
  auto record = [&](double t) {
    if (trial.record_interval <= 0.0 || t + 1e-9 < next_record) return;
    next_record += trial.record_interval;
    result->states.push_back({t, data->arm_positions(), data->hand_positions(), data->object_pose(),
                              data->wrist_pose()});
  };
  record(0.0);
  for (long n = 0; n < steps; ++n) {
    const double t = n * h;
    const TrajectorySample now = SampleAt(trajectory, t);
    const TrajectorySample next = SampleAt(trajectory, t + h);
    data->SetArmCommand(now.arm, (next.arm - now.arm) / h);
    data->SetHandCommand(now.hand);
    try {
      data->Step();
    } catch (const std::runtime_error& e) {
      return OdeFailureVerdict(data->time(), e.what());
    }
    if (auto verdict = EarlyVerdict(*data, model.robot().arm, trial)) return verdict;
    WatchStep(*data, trial, watch);
    record(data->time());
    if (AtRestForGood(*data, t_motion)) break;
  }
  return std::nullopt;
}

}  // namespace

bool MujocoTrialOptions::IsValid(std::string* why) const {
  if (!(std::isfinite(time_step) && time_step >= 0.0 && time_step <= 0.02)) {
    if (why) *why = "mujoco time_step (s, 0 or up to 0.02) = " + std::to_string(time_step);
    return false;
  }
  return true;
}

TrialResult RunMujocoTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                           const TrialOptions& trial, const MujocoTrialOptions& options) {
  RequireValid(trial, "invalid trial option");
  RequireValid(options, "invalid MuJoCo trial option");
  if (trajectory.samples.empty()) throw InputError("the trajectory has no samples");
  const auto wall_start = WallClock::now();
  const double cpu_start = ThreadCpuSeconds();
  MjcfOptions mjcf_options;
  mjcf_options.time_step = trial.time_step > 0.0     ? trial.time_step
                           : options.time_step > 0.0 ? options.time_step
                                                     : 0.001;
  mjcf_options.servo = options.servo;
  mjcf_options.physics = trial.physics;
  const MjcfModel mjcf = ExportMjcf(model, trajectory.placement(), mjcf_options);
  const MujocoModel mujoco(model, mjcf);
  MujocoData data(mujoco, trajectory.samples.front().arm, trajectory.samples.front().hand);

  TrialResult result;
  result.counts = data.counts();
  const Eigen::Isometry3d X_WO_rest = model.scene().ObjectPose(trajectory.placement());
  const double t_motion = trajectory.duration();
  result.planned_time = t_motion + trial.hold;
  TrialWatch watch = StartTrialWatch(X_WO_rest);
  const std::optional<TrialVerdict> early =
      PlayTrial(model, trajectory, trial, mjcf_options.time_step, &data, &watch, &result);

  result.max_lift = watch.max_lift;
  result.max_penetration = watch.max_penetration;
  result.simulated_time = data.time();
  result.final_object_pose = data.object_pose();
  result.lift = result.final_object_pose.translation().z() - X_WO_rest.translation().z();
  result.statistics = data.statistics();
  result.hold = MeasureHold(data, watch);
  const TrialVerdict verdict =
      early ? *early : JudgeTrial(data, watch, result.simulated_time - t_motion, trial);
  result.outcome = verdict.outcome;
  result.reason = verdict.reason;
  result.wall_time = SecondsSince(wall_start);
  result.cpu_time = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace graspsynth
