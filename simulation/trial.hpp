#pragma once

/// @file
/// One grasp-and-lift trial: a joint trajectory (reach -> grasp -> lift) played through the
/// robot's controller in the ODE world, then held, and judged as DESIGN.md defines success:
/// after the lift and a hold of at least 1 s, the object's centre is at least 5 cm above its
/// resting height and the object touches only the hand. Expected failures are results with a
/// reason, never exceptions; a simulation that became unstable is a failure, never a success.
///
/// Two fidelities that must agree on every outcome (benchmarks/README.md, "Simulation"):
/// - kFull: the arm is a chain of dynamic, motor-driven links in the same solve as the hand
///   and the object, every step simulated at 1 ms, no early stop;
/// - kFast: the arm follows the controller kinematically (it is 35 kg against a 0.4 kg
///   object, and its shoulder and elbow motors of 80-200 N m do not yield; its wrist's of
///   10-15 N m can, which kFastWristDynamic models: docs/architecture.md, "Robustness under the
///   contact model", measures what that changes), steps of 4 ms, free space is not simulated in
///   contact detail (the controller model moves arm and fingers and collisions are checked until
///   anything touches: free space ends at the first contact, which is resolved from the next step
///   on), and the trial stops as soon as its outcome is decided.

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "motion/joint_trajectory.hpp"
#include "simulation/simulation_data.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial_judge.hpp"

namespace graspsynth {

/// Simulation detail of a trial (see the file comment).
enum class Fidelity {
  kFast,
  kFull,
  /// kFast with the wrist joints E2, W1 and W2 as motor-driven dynamic links
  /// (ArmMode::kWristDynamic): their 10-15 N m motors yield to a grasp as they do in kFull.
  kFastWristDynamic,
};

/// Options of one trial; the judgement's thresholds are those of the base (TrialJudgeOptions).
struct TrialOptions : TrialJudgeOptions {
  Fidelity fidelity = Fidelity::kFast;
  /// Physics step, s; 0 picks the fidelity's default (kFast 0.004, kFull 0.001).
  double time_step = 0.0;
  /// Time the last command is held after the trajectory ends, s (DESIGN.md: >= 1 s).
  double hold = 1.0;
  /// Record the state every this many seconds (0: no record).
  double record_interval = 0.0;
  /// Changes of the physics in this trial's world (WorldOptions::physics; none by default).
  PhysicsVariation physics;
  /// kFast: each finger on a kinematic mount of its own (WorldOptions::finger_mounts).
  bool finger_mounts = true;
  /// kFast: the structured solve (WorldOptions::structured_solver).
  bool structured_solver = true;
  /// ODE's dSpaceCollide instead of the broad phase (WorldOptions::ode_broad_phase).
  bool ode_broad_phase = false;

  /// True when every value is finite and in range; otherwise false with the reason.
  bool IsValid(std::string* why) const;
  /// The physics step this trial uses, s.
  double step() const;
};

/// One recorded state of a trial.
struct TrialState {
  double t = 0.0;                                          ///< s
  Vector7d arm = Vector7d::Zero();                         ///< measured arm joints, rad
  HandVector hand = HandVector::Zero();                    ///< measured f0..f15, rad
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();  ///< object pose
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();  ///< wrist (hand mount) pose
};

/// What a trial found.
struct TrialResult {
  TrialOutcome outcome = TrialOutcome::kUnstable;
  std::string reason;            ///< one sentence, with the figures that decided it
  double lift = 0.0;             ///< object centre above its rest height at the end, m
  double max_lift = 0.0;         ///< highest it got, m
  double max_penetration = 0.0;  ///< deepest contact involving the object, m
  double simulated_time = 0.0;   ///< s
  double planned_time = 0.0;     ///< trajectory + hold, s (more than simulated if stopped)
  double wall_time = 0.0;        ///< s
  double cpu_time = 0.0;         ///< s of the calling thread's CPU time
  Eigen::Isometry3d final_object_pose = Eigen::Isometry3d::Identity();
  HoldQuality hold;  ///< how the object sits in the hand at the end
  /// The object-hand contacts of the last step, with their forces (the hold margin's,
  /// gate/hold_margin.hpp); empty when nothing touched the object at the end.
  std::vector<HandObjectContact> end_contacts;
  StepStatistics statistics;       ///< steps and where their time went
  WorldCounts counts;              ///< bodies, joints, geoms of the world
  std::vector<TrialState> states;  ///< when recording

  bool success() const { return outcome == TrialOutcome::kSuccess; }
  /// One line: outcome, reason, lift, steps, speed (simulated time per CPU second).
  std::string BriefReport() const;
};

/// Called after every step with the world (for tests and instrumentation).
using StepObserver = std::function<void(SimulationData&)>;

/// Plays `trajectory` (a valid one: ParseJointTrajectory + CheckJointLimits) for the object at
/// trajectory.placement() from its first sample, holds its last command for
/// options.hold and judges the outcome. Throws InputError only for invalid options.
TrialResult RunTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                     const TrialOptions& options = {}, const StepObserver& observer = {});

/// The end of a trial, whatever engine played it (RunTrial, and the MuJoCo trial of
/// simulation_mujoco/): from the world after its last step and the watch, the result's highest
/// lift and deepest penetration, simulated time, final object pose and lift, hold, and outcome
/// with its reason: `early` when the play ended with a verdict, else the judgement after the
/// last command was held for the time past `t_motion` (s). The caller fills the rest (states,
/// counts, the step statistics, the times). `hand` numbers the world's hand links.
void FinishTrial(const JudgedWorld& world, const HandModel& hand, const TrialWatch& watch,
                 double t_motion, const std::optional<TrialVerdict>& early,
                 const TrialJudgeOptions& options, TrialResult* result);

}  // namespace graspsynth
