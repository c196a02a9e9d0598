#pragma once

/// @file
/// The physics gate: a synthesized joint trajectory is simulated nominally (RunTrial) and
/// under perturbation (EvaluateRobustness) before it may be written; it passes when the nominal
/// trial succeeds and the robustness score reaches the threshold, and, with MuJoCo among its
/// engines (MujocoGateOptions), when the MuJoCo sweep's success fraction reaches its own. The
/// grasp's quality (CGAL, Ferrari-Canny epsilon and hull volume; gate/grasp_quality.hpp) comes
/// from the hand-object contacts of the nominal trial's last step that had any (the hold at the
/// top, for a grasp that lifts), about the object's centre of mass.

#include <optional>
#include <string>
#include <vector>

#include "gate/grasp_quality.hpp"
#include "gate/hold_margin.hpp"
#include "simulation/robustness.hpp"
#include "simulation_mujoco/mujoco_sweep.hpp"

namespace graspsynth {

/// The gate's engines beyond ODE (issue 45): with `enabled` (`--engines ode,mujoco`), a grasp
/// that ODE passes must also hold in MuJoCo under the sweep's contact settings and servo
/// mappings (simulation_mujoco/mujoco_sweep.hpp). ODE stays the validator of every default run.
struct MujocoGateOptions {
  bool enabled = false;  ///< MuJoCo judges too (off: ODE alone, the default)
  /// The share of the sweep's runs that must succeed, [0, 1]. 0.95, the bar: with 16
  /// runs it allows no failure (15/16 = 0.9375), so every contact model and servo mapping holds.
  double min_success = 0.95;
  /// The sweep's contact settings and servo mappings (the defaults: all 8 x stiff, soft); its
  /// trial is the gate's nominal trial's and its threads the robustness replays'.
  std::vector<MujocoContactSetting> settings = AllMujocoContactSettings();
  std::vector<MujocoServo> servos = {MujocoServo::kStiff, MujocoServo::kSoft};

  /// True when min_success is in [0, 1] and the lists are valid MujocoSweepOptions lists.
  bool IsValid(std::string* why) const;
};

/// Options of RunPhysicsGate.
struct PhysicsGateOptions {
  /// The perturbed replays, passed to EvaluateRobustness whole: their number (`trials`, here
  /// >= 0, 0: nominal only), seed, threads and perturbation; its `trial` is the nominal
  /// trial's too.
  RobustnessOptions robustness = RobustnessOptions::WithTrials(30);
  /// Replays per end of each physics factor's range for the sensitivity table, >= 0 (0: no
  /// table); run when the robustness replays run, with the robustness' seed and perturbation.
  int sensitivity_trials = 0;
  double min_robustness = 0.8;  ///< success fraction needed, [0, 1]
  bool require_nominal = true;  ///< the nominal trial must succeed
  GraspQualityOptions quality;
  MujocoGateOptions mujoco;  ///< MuJoCo as a second engine (off by default)
  /// The hold margin's thresholds and whether the gate requires them (gate/hold_margin.hpp);
  /// required, a nominal trial that succeeds with a margin below a threshold fails the gate,
  /// without its perturbed replays.
  HoldMarginOptions hold_margin;

  bool IsValid(std::string* why) const;
};

/// The gate's verdict and its figures.
struct PhysicsGateResult {
  bool passed = false;
  std::string reason;  ///< why it passed or failed, one sentence with the figures
  TrialResult nominal;
  bool robustness_run = false;
  RobustnessResult robustness;
  std::optional<SensitivityResult> sensitivity;  ///< with options.sensitivity_trials > 0
  std::vector<GraspContact> contacts;            ///< the contacts the quality was computed from
  GraspQuality quality;
  /// The MuJoCo sweep, with options.mujoco.enabled when ODE's nominal trial succeeded (or was
  /// not required) and ODE's robustness reached its threshold.
  std::optional<MujocoSweepResult> mujoco;
  HoldMargin hold_margin;  ///< the nominal trial's hold margin
  /// The thresholds the hold margin misses (HoldMarginShortfall); "" when it meets them all.
  std::string hold_margin_shortfall;
  HoldMarginOptions hold_margin_options;  ///< the thresholds it was judged by (the options')
  double time_s = 0.0;                    ///< wall time of the gate
};

/// Simulates `trajectory` (limit-checked) in `model` and judges it. `progress` counts the
/// perturbed replays, then the sensitivity table's. Throws InputError for invalid options.
PhysicsGateResult RunPhysicsGate(const SimulationModel& model, const JointTrajectory& trajectory,
                                 const PhysicsGateOptions& options = {},
                                 const ProgressCallback& progress = {});

}  // namespace graspsynth
