#pragma once

/// @file
/// A grasp-and-lift trial in MuJoCo (docs/mujoco.md): the trajectory played through the same
/// controller as the ODE trial (simulation/trial.hpp) in the exported model
/// (simulation_mujoco/mjcf_export.hpp), held, and judged by the same functions
/// (simulation/trial_judge.hpp) from the MuJoCo world's state. Every step is simulated (MuJoCo
/// has no free-space shortcut here); like the fast ODE trial, it stops once the hand holds still
/// and the object lies untouched on the table. Expected failures are results, never exceptions.

#include <string>

#include "motion/joint_trajectory.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"
#include "simulation_mujoco/mjcf_export.hpp"

namespace graspsynth {

/// Options of a MuJoCo trial beyond the trial's own (TrialOptions: its hold, judgement, physics
/// variation and recording; its fidelity and ODE switches do not apply).
struct MujocoTrialOptions {
  /// MuJoCo's step, s; 0: 1 ms (TrialOptions::time_step, when set, wins).
  double time_step = 0.0;
  MujocoServo servo = MujocoServo::kStiff;  ///< the finger servos' mapping
  /// MuJoCo's contact settings of the model (the defaults: docs/mujoco.md's mapping).
  MjcfContact contact;

  /// True when the step is finite and in [0, 0.02] s and the contact settings valid.
  bool IsValid(std::string* why) const;
};

/// The exported model's options of a MuJoCo trial with `trial` and `options` (the step:
/// trial.time_step when set, else options.time_step, else 1 ms; the servo mapping, the contact
/// settings and the trial's physics variation).
MjcfOptions MujocoTrialMjcfOptions(const TrialOptions& trial, const MujocoTrialOptions& options);

/// Plays `trajectory` (a valid one) for the object at trajectory.placement() in MuJoCo, holds
/// its last command for trial.hold and judges it as RunTrial does. Throws InputError for invalid
/// options and when this build has no MuJoCo (MujocoAvailable()).
TrialResult RunMujocoTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                           const TrialOptions& trial, const MujocoTrialOptions& options = {});

}  // namespace graspsynth
