#pragma once

/// @file
/// Robustness of a grasp trajectory (paper IV-B): N perturbed replays (time scaling and
/// waypoint noise, simulation/perturbation.hpp; with the physics perturbation enabled, also
/// friction, contact stiffness and damping, the object's mass and centre of mass, the finger
/// servos' force and the step, simulation/physics_perturbation.hpp), each a full grasp-and-lift
/// trial; the score is the success fraction with its 95% Wilson interval. The sensitivity of a
/// grasp (EvaluateSensitivity) replays it with one physics factor at a time at an end of its
/// range.
///
/// Trials run in parallel, one ODE world per trial on a worker thread (each world has its own
/// threading implementation: simulation_data.hpp). Trial i draws its perturbation from the
/// random stream (seed, i) alone and its world is built fresh, so every trial's result - down
/// to the last bit of the final object pose - is the same whatever the number of threads.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "simulation/perturbation.hpp"
#include "simulation/trial.hpp"

namespace graspsynth {

/// Options of a robustness evaluation.
struct RobustnessOptions {
  int trials = 100;   ///< perturbed replays, >= 1
  uint64_t seed = 1;  ///< the whole evaluation is a function of the seed
  int threads = 0;    ///< worker threads; 0: one per hardware thread
  PerturbationOptions perturbation;
  TrialOptions trial;

  bool IsValid(std::string* why) const;

  /// The defaults with `count` replays (the defaults of the options that nest these).
  static RobustnessOptions WithTrials(int count) {
    RobustnessOptions o;
    o.trials = count;
    return o;
  }
};

/// One perturbed replay.
struct RobustnessTrial {
  int index = 0;
  double time_scale = 1.0;
  PhysicsDraw physics;  ///< the replay's physics (all nominal without the physics perturbation)
  TrialOutcome outcome = TrialOutcome::kUnstable;
  std::string reason;
  double lift = 0.0;  ///< m
  Eigen::Isometry3d final_object_pose = Eigen::Isometry3d::Identity();
  HoldQuality hold;             ///< how the object sat in the hand at the end
  double simulated_time = 0.0;  ///< s
  double wall_time = 0.0;       ///< s
  double cpu_time = 0.0;        ///< s
  long dynamic_steps = 0;
  long kinematic_steps = 0;

  bool success() const { return outcome == TrialOutcome::kSuccess; }
};

/// The score and every trial.
struct RobustnessResult {
  std::vector<RobustnessTrial> trials;  ///< in index order
  int successes = 0;
  double score = 0.0;           ///< successes / trials
  Interval ci95;                ///< Wilson score interval of the success probability
  int threads = 0;              ///< worker threads used
  double wall_time = 0.0;       ///< s
  double simulated_time = 0.0;  ///< s, summed over trials
  double cpu_time = 0.0;        ///< s, summed over trials (simulated / cpu: speed per core)
};

/// The Wilson score interval for `successes` out of `n` at normal quantile z (1.959964 for
/// 95%). [0, 1] when n is 0.
Interval WilsonInterval(int successes, int n, double z = 1.959963984540054);

/// Progress: trials done so far and the total. Called from the worker threads, one call at a
/// time.
using ProgressCallback = std::function<void(int done, int total)>;

/// Runs options.trials perturbed replays of `nominal`. Throws InputError for invalid options;
/// failed and infeasible replays are results.
RobustnessResult EvaluateRobustness(const SimulationModel& model, const JointTrajectory& nominal,
                                    const RobustnessOptions& options,
                                    const ProgressCallback& progress = {});

/// A rule that ends an evaluation early: called with the successes and failures of the
/// replays 0..k-1 for k = 1, 2, ... in index order; true means the replays from k on cannot
/// change what the caller wants to know.
using StopRule = std::function<bool(int successes, int failures)>;

/// EvaluateRobustness() that stops after the first k replays for which `stop` holds (all
/// options.trials when it never does): `trials` holds replays 0..k-1 and the score and interval
/// are of those k. Replays run in parallel, so a few beyond k may run and are dropped; k and
/// every figure are the same whatever the thread count.
RobustnessResult EvaluateRobustnessUntil(const SimulationModel& model,
                                         const JointTrajectory& nominal,
                                         const RobustnessOptions& options, const StopRule& stop,
                                         const ProgressCallback& progress = {});

/// The failed replays by outcome, in the outcome enum's order, e.g. "dropped 3, not_lifted 1";
/// empty when every replay succeeded.
std::string FailureSummary(const RobustnessResult& result);

/// Runs trial `index` of an evaluation alone (what EvaluateRobustness runs for it).
RobustnessTrial RunRobustnessTrial(const SimulationModel& model, const JointTrajectory& nominal,
                                   const RobustnessOptions& options, int index);

/// Replay `index`'s motion (the same time scale and noise as RunRobustnessTrial's) with the
/// given physics instead of a drawn one.
RobustnessTrial RunReplayWithPhysics(const SimulationModel& model, const JointTrajectory& nominal,
                                     const RobustnessOptions& options, int index,
                                     const PhysicsDraw& physics);

/// The success rate of a grasp with one physics factor at one end of its range.
struct SensitivityCell {
  PhysicsDraw physics;
  int trials = 0;
  int successes = 0;
  std::string failures;  ///< FailureSummary of the cell's replays

  double rate() const { return trials > 0 ? static_cast<double>(successes) / trials : 0.0; }
};

/// One factor's row of the sensitivity table: the grasp at each end of the factor's range.
struct SensitivityRow {
  PhysicsFactor factor = PhysicsFactor::kHandFriction;
  SensitivityCell low;
  SensitivityCell high;
};

/// What a grasp depends on: for every factor (AllPhysicsFactors, in that order), its low and
/// its high end.
struct SensitivityResult {
  int trials_per_cell = 0;
  std::vector<SensitivityRow> rows;
  double wall_time = 0.0;  ///< s
};

/// Replays `nominal` options.trials times in each cell: the motion perturbations are those of
/// the robustness evaluation's first options.trials replays (the same seed and streams), the
/// physics that of the cell (PhysicsAtEnd with options.perturbation.physics's ranges, whether
/// or not it is enabled; the centre of mass moves along SensitivityComDirection). Progress
/// counts replays over all cells. Throws InputError for invalid options.
SensitivityResult EvaluateSensitivity(const SimulationModel& model, const JointTrajectory& nominal,
                                      const RobustnessOptions& options,
                                      const ProgressCallback& progress = {});

}  // namespace graspsynth
