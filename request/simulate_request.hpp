#pragma once

/// @file
/// The requests of `graspsynth simulate` (SimulateRequest) and of Python's simulate and
/// robustness (TrialRequest, RobustnessRequest; also Simulation.trial and
/// Simulation.robustness): a joint trajectory played in the ODE world, once and under
/// perturbation. Their options are described once (the trial's settings, the seed, the threads
/// and the physics perturbation are the same descriptions in each) and turned into the
/// library's options once (ToTrialOptions, ToRobustnessOptions), for both front ends. The
/// trajectory, robot, scene and object are not options, nor are the command's output files.

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "gate/hold_margin.hpp"
#include "motion/scripted_grasp.hpp"
#include "request/mujoco_request.hpp"
#include "request/option.hpp"
#include "simulation/robustness.hpp"
#include "simulation/trial.hpp"

namespace graspsynth::request {

/// The settings of a trial every simulation request has: the fidelity, the step and the hold.
struct TrialSettings {
  std::string fidelity = "fast";                ///< fast, fast-wrist or full
  double time_step = TrialOptions{}.time_step;  ///< s; 0: the fidelity's step
  double hold = TrialOptions{}.hold;            ///< s the last command is held
};

/// What `graspsynth simulate` plays and how; the defaults are the library's.
struct SimulateRequest {
  std::optional<Eigen::Vector2d> at;  ///< the object centre on the table, m; none: the file's
  int perturb = 0;                    ///< perturbed replays (0: the nominal trial only)
  int sensitivity = 0;                ///< replays per end of each physics factor's range
  uint64_t seed = RobustnessOptions{}.seed;
  int threads = RobustnessOptions{}.threads;  ///< 0: all cores
  double record_interval = 0.01;              ///< s between recorded states (with --record)
  TrialSettings trial;
  EngineSettings engine;  ///< the engine of the nominal trial (docs/mujoco.md)
  double time_scale_min = PerturbationOptions{}.time_scale_min;
  double time_scale_max = PerturbationOptions{}.time_scale_max;
  double position_noise = PerturbationOptions{}.position_sigma;  ///< m
  double orientation_noise_deg = PerturbationOptions{}.orientation_sigma / kDeg;
  double finger_noise_deg = PerturbationOptions{}.finger_sigma / kDeg;
  PhysicsPerturbationOptions physics = PerturbationOptions{}.physics;
  /// The nominal trial's hold margin: its thresholds for the report, and whether a miss makes
  /// the command exit 1.
  HoldMarginOptions hold_margin;
};

/// What Python's simulate (Simulation.trial) plays: one nominal trial.
struct TrialRequest {
  TrialSettings trial;
  double record_interval = 0.0;  ///< s between recorded states; 0: none recorded
};

/// What Python's robustness (Simulation.robustness) replays: the same replays as
/// `graspsynth simulate --perturb TRIALS --seed SEED`, with the motion noise scaled.
struct RobustnessRequest {
  int trials = 20;
  uint64_t seed = RobustnessOptions{}.seed;
  int threads = RobustnessOptions{}.threads;  ///< 0: all cores
  double noise_scale = 1.0;                   ///< factor on the motion noise
  TrialSettings trial;
  PhysicsPerturbationOptions physics = PerturbationOptions{}.physics;
};

/// What `graspsynth scripted-grasp` builds: the hand-made grasp trajectory
/// (motion/scripted_grasp.hpp).
struct ScriptedGraspRequest {
  double theta = ScriptedGraspOptions{}.theta_deg;            ///< object orientation, deg
  double grasp_radius = ScriptedGraspOptions{}.grasp_radius;  ///< m from the object centre
  bool keep_open = false;  ///< the hand stays open (a trajectory that must fail)
};

/// The options of SimulateRequest, TrialRequest, RobustnessRequest and ScriptedGraspRequest, in the
/// order the front ends list them.
const OptionList<SimulateRequest>& SimulateOptions();
const OptionList<TrialRequest>& TrialRequestOptions();
const OptionList<RobustnessRequest>& RobustnessRequestOptions();
const OptionList<ScriptedGraspRequest>& ScriptedGraspRequestOptions();

/// The scripted grasp's options of `request`. Throws InputError for invalid ones.
ScriptedGraspOptions ToScriptedGraspOptions(const ScriptedGraspRequest& request);

/// The trial's options of `settings`. Throws InputError "bad simulation option: ..." for an
/// invalid combination.
TrialOptions ToTrialOptions(const TrialSettings& settings);
/// The nominal trial's options of `request` (its record interval included).
TrialOptions ToTrialOptions(const TrialRequest& request);
/// The nominal trial's options of `request` (without the record interval, which only --record
/// uses).
TrialOptions ToTrialOptions(const SimulateRequest& request);

/// The perturbed replays' options of `request`: max(perturb, 1) replays. Throws InputError
/// "bad perturbation option: ..." for invalid ones.
RobustnessOptions ToRobustnessOptions(const SimulateRequest& request);
/// The perturbed replays' options of `request`. Throws InputError for invalid ones.
RobustnessOptions ToRobustnessOptions(const RobustnessRequest& request);

}  // namespace graspsynth::request
