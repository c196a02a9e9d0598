#include "simulation/robustness.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <mutex>

#include "common/errors.hpp"
#include "common/parallel.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
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

namespace {

// Replay `index`: its motion from the stream (seed, index), then its physics, drawn from the
// same stream after the motion (or `fixed`).
RobustnessTrial RunReplay(const SimulationModel& model, const JointTrajectory& nominal,
                          const RobustnessOptions& options, int index, const PhysicsDraw* fixed) {
  SplitMix64 rng = SplitMix64::ForStream(options.seed, static_cast<uint64_t>(index));
  const PerturbedTrajectory p =
      PerturbTrajectory(model.robot(), nominal, options.perturbation, rng);
  RobustnessTrial t;
  t.index = index;
  t.time_scale = p.time_scale;
  if (!p.ok) {
    t.outcome = TrialOutcome::kJointLimit;
    t.reason = "infeasible replay: " + p.message;
    t.final_object_pose = model.scene().ObjectPose(nominal.placement());
    return t;
  }
  t.physics = fixed ? *fixed : DrawPhysics(options.perturbation.physics, rng);
  TrialOptions trial = options.trial;
  trial.physics = t.physics.variation;
  if (t.physics.time_step > 0.0) trial.time_step = t.physics.time_step;
  const TrialResult r = RunTrial(model, p.trajectory, trial);
  t.outcome = r.outcome;
  t.reason = r.reason;
  t.lift = r.lift;
  t.final_object_pose = r.final_object_pose;
  t.hold = r.hold;
  t.simulated_time = r.simulated_time;
  t.wall_time = r.wall_time;
  t.cpu_time = r.cpu_time;
  t.dynamic_steps = r.statistics.dynamic_steps;
  t.kinematic_steps = r.statistics.kinematic_steps;
  return t;
}

void Validate(const RobustnessOptions& options) {
  RequireValid(options, "invalid robustness option");
}

// Runs `count` replays on options.threads workers, reporting progress per finished replay.
void RunReplays(int count, const RobustnessOptions& options, const std::function<void(int)>& job,
                const ProgressCallback& progress) {
  ParallelFor(count, options.threads, job, [&](int finished) {
    if (progress) progress(finished, count);
  });
}

}  // namespace

RobustnessTrial RunRobustnessTrial(const SimulationModel& model, const JointTrajectory& nominal,
                                   const RobustnessOptions& options, int index) {
  return RunReplay(model, nominal, options, index, nullptr);
}

RobustnessTrial RunReplayWithPhysics(const SimulationModel& model, const JointTrajectory& nominal,
                                     const RobustnessOptions& options, int index,
                                     const PhysicsDraw& physics) {
  return RunReplay(model, nominal, options, index, &physics);
}

RobustnessResult EvaluateRobustness(const SimulationModel& model, const JointTrajectory& nominal,
                                    const RobustnessOptions& options,
                                    const ProgressCallback& progress) {
  return EvaluateRobustnessUntil(model, nominal, options, {}, progress);
}

RobustnessResult EvaluateRobustnessUntil(const SimulationModel& model,
                                         const JointTrajectory& nominal,
                                         const RobustnessOptions& options, const StopRule& stop,
                                         const ProgressCallback& progress) {
  Validate(options);
  const auto start = std::chrono::steady_clock::now();
  const int n = options.trials;
  RobustnessResult result;
  result.trials.resize(static_cast<size_t>(n));
  result.threads = WorkerCount(options.threads, n);
  // The stop rule sees the finished prefix 0..prefix-1 grow in index order; `end` is where the
  // evaluation ends (n until the rule holds). Replays at or past `end` are not started.
  std::mutex mutex;
  std::vector<char> finished(static_cast<size_t>(n), 0);
  int prefix = 0, successes = 0;
  std::atomic<int> end{n};  // written under `mutex`; read without it to skip replays
  RunReplays(n, options,
             [&](int i) {
               if (i >= end) return;
               RobustnessTrial t = RunRobustnessTrial(model, nominal, options, i);
               std::lock_guard<std::mutex> lock(mutex);
               result.trials[static_cast<size_t>(i)] = std::move(t);
               finished[static_cast<size_t>(i)] = 1;
               while (prefix < end && finished[static_cast<size_t>(prefix)]) {
                 successes += result.trials[static_cast<size_t>(prefix)].success();
                 ++prefix;
                 if (stop && stop(successes, prefix - successes)) end = prefix;
               }
               if (progress)
                 progress(static_cast<int>(std::count(finished.begin(), finished.begin() + end, 1)),
                          end);
             },
             {});
  result.trials.resize(static_cast<size_t>(end.load()));

  for (const RobustnessTrial& t : result.trials) {
    result.successes += t.success();
    result.simulated_time += t.simulated_time;
    result.cpu_time += t.cpu_time;
  }
  result.score = static_cast<double>(result.successes) / end;
  result.ci95 = WilsonInterval(result.successes, end);
  result.wall_time = SecondsSince(start);
  return result;
}

SensitivityResult EvaluateSensitivity(const SimulationModel& model, const JointTrajectory& nominal,
                                      const RobustnessOptions& options,
                                      const ProgressCallback& progress) {
  Validate(options);
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Vector3d com_direction = SensitivityComDirection(model);
  SensitivityResult result;
  result.trials_per_cell = options.trials;
  std::vector<SensitivityCell*> cells;  // by factor, low end first
  for (PhysicsFactor factor : AllPhysicsFactors()) {
    SensitivityRow& row = result.rows.emplace_back();
    row.factor = factor;
    for (bool high : {false, true}) {
      SensitivityCell& cell = high ? row.high : row.low;
      cell.physics = PhysicsAtEnd(options.perturbation.physics, factor, high, com_direction);
      cell.trials = options.trials;
    }
  }
  for (SensitivityRow& row : result.rows) cells.insert(cells.end(), {&row.low, &row.high});
  const int n = options.trials;
  std::vector<RobustnessResult> replays(cells.size());
  for (RobustnessResult& r : replays) r.trials.resize(static_cast<size_t>(n));
  RunReplays(
      static_cast<int>(cells.size()) * n, options,
      [&](int job) {
        const size_t c = static_cast<size_t>(job / n);
        replays[c].trials[static_cast<size_t>(job % n)] =
            RunReplayWithPhysics(model, nominal, options, job % n, cells[c]->physics);
      },
      progress);
  for (size_t c = 0; c < cells.size(); ++c) {
    for (const RobustnessTrial& t : replays[c].trials) cells[c]->successes += t.success();
    cells[c]->failures = FailureSummary(replays[c]);
  }
  result.wall_time = SecondsSince(start);
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
