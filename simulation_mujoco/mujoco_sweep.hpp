#pragma once

/// @file
/// A grasp in MuJoCo under several contact models (issue 45): the trajectory's trial
/// (simulation_mujoco/mujoco_trial.hpp) under each of a named set of MuJoCo contact settings
/// (MujocoContactSetting, each one documented change of the exported model) crossed with the two
/// mappings of the finger servos (MujocoServo: stiff and soft), as ODE's replays perturb ODE's
/// physics. Each run reports its outcome, reason, lift and slip in the hand; the summary is the
/// success fraction, the slip of the successful runs (median and worst) and the runs that fail.
/// Every run is independent and deterministic, so the result is the same whatever the thread
/// count. Expected failures are results; only invalid options throw.

#include <string>
#include <string_view>
#include <vector>

#include "motion/joint_trajectory.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"
#include "simulation_mujoco/mjcf_export.hpp"
#include "simulation_mujoco/mujoco_trial.hpp"

namespace graspsynth {

/// One MuJoCo contact setting of the sweep: one change of the exported model from the mapping
/// of ODE's contacts (docs/mujoco.md, "Contacts"). Each spans a choice a MuJoCo user could
/// plausibly make for the same rubber-on-metal grip.
enum class MujocoContactSetting {
  kNominal,  ///< "nominal": the mapping as exported (1 ms, solref 2 ms, elliptic, impratio 10)
  kSoftReference,    ///< "soft_reference": solref's time constant x2 (4 ms): softer finger pads
  kMujocoImpedance,  ///< "mujoco_impedance": solimp 0.9 0.95 0.001, MuJoCo's own default
  kPyramidalCone,    ///< "pyramidal": cone="pyramidal", MuJoCo's default cone (condim 3: a diamond)
  kSoftFriction,     ///< "impratio_1": impratio 1, MuJoCo's default: friction as soft as the normal
  kFineStep,     ///< "step_0.5ms": 0.5 ms; solref's floor halves too (1.16 ms: a harder contact)
  kCoarseStep,   ///< "step_2ms": 2 ms; solref's floor of two steps makes it 4 ms
  kLowFriction,  ///< "friction_0.75": the object-hand friction x0.75 (ODE's replays' low end)
};

/// The number of MujocoContactSetting values.
inline constexpr int kMujocoContactSettings = 8;

/// The setting's name ("nominal", "soft_reference", ...; the enum's comments).
std::string_view ToString(MujocoContactSetting setting);
/// The setting named `text`; throws InputError naming `what` and the value otherwise.
MujocoContactSetting ParseMujocoContactSetting(std::string_view text, std::string_view what);
/// Every setting, in the enum's order.
std::vector<MujocoContactSetting> AllMujocoContactSettings();

/// Changes `trial` and `mujoco` (the options of a nominal MuJoCo trial) as `setting` says: the
/// MuJoCo step (`mujoco->time_step`, with `trial->time_step` cleared so that it wins), the
/// contact settings (`mujoco->contact`) or the object-hand friction (`trial->physics`, multiplied).
void ApplyMujocoContactSetting(MujocoContactSetting setting, TrialOptions* trial,
                               MujocoTrialOptions* mujoco);

/// Options of EvaluateMujocoSweep.
struct MujocoSweepOptions {
  /// Each run's trial (hold, judgement, physics variation; its time_step, when set, is the
  /// nominal step, else `time_step`).
  TrialOptions trial;
  double time_step = 0.001;  ///< the nominal MuJoCo step, s, in (0, 0.02]
  /// The contact settings, each once, not empty.
  std::vector<MujocoContactSetting> settings = AllMujocoContactSettings();
  /// The finger servos' mappings, each once, not empty.
  std::vector<MujocoServo> servos = {MujocoServo::kStiff, MujocoServo::kSoft};
  int threads = 0;  ///< worker threads, >= 0 (0: all cores); changes no result

  /// True when the trial's options are valid, the step in range, the lists not empty and
  /// without repeats, and threads >= 0.
  bool IsValid(std::string* why) const;
};

/// One run of the sweep.
struct MujocoSweepRun {
  MujocoContactSetting setting = MujocoContactSetting::kNominal;
  MujocoServo servo = MujocoServo::kStiff;
  TrialOutcome outcome = TrialOutcome::kUnstable;
  std::string reason;       ///< the trial's sentence
  double lift = 0.0;        ///< object centre above its rest height at the end, m
  double slip = 0.0;        ///< the object's displacement in the hand since it left the table, m
  double slip_angle = 0.0;  ///< and its rotation, rad (HoldQuality)
  double wall_time = 0.0;   ///< s (not deterministic)

  bool success() const { return outcome == TrialOutcome::kSuccess; }
  /// "setting/servo", e.g. "pyramidal/soft".
  std::string Label() const;
};

/// The sweep's figures over its runs.
struct MujocoSweepSummary {
  int runs = 0;                   ///< settings x servos
  int successes = 0;              ///< runs that succeeded
  double success_fraction = 0.0;  ///< successes / runs
  /// Slip of the successful runs (HoldQuality::slip, m; slip_angle, rad): the median (the
  /// mean of the middle two for an even count) and the largest; 0 without a success.
  double slip_median = 0.0, slip_worst = 0.0;
  double slip_angle_median = 0.0, slip_angle_worst = 0.0;
  /// The failed runs' labels (MujocoSweepRun::Label), comma-separated in run order; "" when none.
  std::string failing;
};

/// The sweep's runs (settings outer, servos inner, in the options' order) and summary.
struct MujocoSweepResult {
  std::vector<MujocoSweepRun> runs;
  MujocoSweepSummary summary;
  int threads = 1;         ///< worker threads used
  double wall_time = 0.0;  ///< s (not deterministic)

  /// One line: "k/n runs held in MuJoCo (fraction), slip median/worst mm, failing: ...".
  std::string BriefReport() const;
};

/// The summary of `runs` (see MujocoSweepSummary).
MujocoSweepSummary SummarizeMujocoSweep(const std::vector<MujocoSweepRun>& runs);

/// Plays `trajectory` (a valid one, its object at trajectory.placement()) in MuJoCo once per
/// setting and servo mapping of `options`. `progress` counts the finished runs. Throws
/// InputError for invalid options and when this build has no MuJoCo (MujocoAvailable()).
MujocoSweepResult EvaluateMujocoSweep(const SimulationModel& model,
                                      const JointTrajectory& trajectory,
                                      const MujocoSweepOptions& options = {},
                                      const ProgressCallback& progress = {});

}  // namespace graspsynth
