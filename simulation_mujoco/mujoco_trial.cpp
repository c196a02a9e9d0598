#include "simulation_mujoco/mujoco_trial.hpp"

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
  return contact.IsValid(why);
}

MjcfOptions MujocoTrialMjcfOptions(const TrialOptions& trial, const MujocoTrialOptions& options) {
  MjcfOptions mjcf_options;
  mjcf_options.time_step = trial.time_step > 0.0     ? trial.time_step
                           : options.time_step > 0.0 ? options.time_step
                                                     : 0.001;
  mjcf_options.servo = options.servo;
  mjcf_options.contact = options.contact;
  mjcf_options.physics = trial.physics;
  return mjcf_options;
}

TrialResult RunMujocoTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                           const TrialOptions& trial, const MujocoTrialOptions& options) {
  RequireValid(trial, "invalid trial option");
  RequireValid(options, "invalid MuJoCo trial option");
  if (trajectory.samples.empty()) throw InputError("the trajectory has no samples");
  const auto wall_start = WallClock::now();
  const double cpu_start = ThreadCpuSeconds();
  const MjcfOptions mjcf_options = MujocoTrialMjcfOptions(trial, options);
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

  FinishTrial(data, model.robot().hand, watch, t_motion, early, trial, &result);
  result.statistics = data.statistics();
  result.wall_time = SecondsSince(wall_start);
  result.cpu_time = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace graspsynth
