#include "simulation/robustness.hpp"

#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <thread>

#include "common/errors.hpp"
#include "simulation/random.hpp"

namespace graspsynth {

bool RobustnessOptions::IsValid(std::string* why) const {
  if (trials < 1) {
    if (why) *why = "trials must be at least 1";
    return false;
  }
  if (threads < 0) {
    if (why) *why = "threads must be >= 0 (0: all cores)";
    return false;
  }
  return perturbation.IsValid(why) && trial.IsValid(why);
}

Interval WilsonInterval(int successes, int n, double z) {
  if (n <= 0) return {0.0, 1.0};
  const double p = static_cast<double>(successes) / n;
  const double z2 = z * z;
  const double denom = 1.0 + z2 / n;
  const double centre = (p + z2 / (2.0 * n)) / denom;
  const double half = z * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n)) / denom;
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

RobustnessTrial RunRobustnessTrial(const SimulationModel& model, const JointTrajectory& nominal,
                                   const RobustnessOptions& options, int index) {
  SplitMix64 rng = SplitMix64::ForStream(options.seed, static_cast<uint64_t>(index));
  const PerturbedTrajectory p =
      PerturbTrajectory(model.robot(), nominal, options.perturbation, rng);
  RobustnessTrial t;
  t.index = index;
  t.time_scale = p.time_scale;
  if (!p.ok) {
    t.outcome = TrialOutcome::kJointLimit;
    t.reason = "infeasible replay: " + p.message;
    t.final_object_pose = model.scene().ObjectPose(nominal.theta_deg * M_PI / 180.0);
    return t;
  }
  const TrialResult r = RunTrial(model, p.trajectory, options.trial);
  t.outcome = r.outcome;
  t.reason = r.reason;
  t.lift = r.lift;
  t.final_object_pose = r.final_object_pose;
  t.simulated_time = r.simulated_time;
  t.wall_time = r.wall_time;
  t.cpu_time = r.cpu_time;
  t.dynamic_steps = r.statistics.dynamic_steps;
  t.kinematic_steps = r.statistics.kinematic_steps;
  return t;
}

RobustnessResult EvaluateRobustness(const SimulationModel& model, const JointTrajectory& nominal,
                                    const RobustnessOptions& options,
                                    const ProgressCallback& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid robustness option: " + why);
  const auto start = std::chrono::steady_clock::now();
  RobustnessResult result;
  result.trials.resize(static_cast<size_t>(options.trials));
  int threads =
      options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
  threads = std::clamp(threads, 1, options.trials);
  result.threads = threads;

  std::atomic<int> next{0};
  std::mutex progress_mutex;
  int done = 0;
  std::exception_ptr error;
  auto worker = [&] {
    try {
      EnsureOdeThread();
      for (int i = next++; i < options.trials; i = next++) {
        result.trials[static_cast<size_t>(i)] = RunRobustnessTrial(model, nominal, options, i);
        std::lock_guard<std::mutex> lock(progress_mutex);
        ++done;
        if (progress) progress(done, options.trials);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      if (!error) error = std::current_exception();
      next = options.trials;  // the others stop after their current trial
    }
  };
  if (threads == 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (int k = 0; k < threads; ++k) pool.emplace_back(worker);
    for (std::thread& t : pool) t.join();
  }
  if (error) std::rethrow_exception(error);

  for (const RobustnessTrial& t : result.trials) {
    result.successes += t.success();
    result.simulated_time += t.simulated_time;
    result.cpu_time += t.cpu_time;
  }
  result.score = static_cast<double>(result.successes) / options.trials;
  result.ci95 = WilsonInterval(result.successes, options.trials);
  result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

std::string FailureSummary(const RobustnessResult& result) {
  std::map<TrialOutcome, int> counts;
  for (const RobustnessTrial& t : result.trials) {
    if (!t.success()) ++counts[t.outcome];
  }
  std::string text;
  for (const auto& [outcome, n] : counts) {
    if (!text.empty()) text += ", ";
    text += std::string(ToString(outcome)) + " " + std::to_string(n);
  }
  return text;
}

}  // namespace graspsynth
