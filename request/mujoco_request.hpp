#pragma once

/// @file
/// The MuJoCo engine's requests (docs/mujoco.md): `graspsynth export-mjcf`'s (ExportMjcfRequest)
/// and the engine settings of `graspsynth simulate` (SimulateRequest's engine and
/// mujoco_servo, described here once). The trajectory, robot, scene and object are not options,
/// nor is the output file.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "request/option.hpp"
#include "simulation_mujoco/mjcf_export.hpp"
#include "simulation_mujoco/mujoco_trial.hpp"

namespace graspsynth::request {

/// The physics engine of a simulation request and the MuJoCo servo mapping.
struct EngineSettings {
  std::string engine = "ode";          ///< ode or mujoco
  std::string mujoco_servo = "stiff";  ///< stiff or soft (MujocoServo)
};

/// What `graspsynth export-mjcf` writes.
struct ExportMjcfRequest {
  /// Object orientation, deg; none: the trajectory's (and 0 without a trajectory).
  std::optional<double> theta;
  std::optional<Eigen::Vector2d> at;  ///< the object centre on the table, m; none: the scene's
  std::string mujoco_servo = "stiff";
  double time_step = MjcfOptions{}.time_step;  ///< MuJoCo's step, s
};

/// The engine options of request type R (engine, mujoco_servo) through `ref`, for
/// SimulateRequest.
template <class R, class F>
void AppendEngineOptions(F ref, OptionList<R>* list) {
  list->push_back(FieldOption<R>(
      WithChoices(MakeInfo("engine", OptionKind::kText,
                           "Physics engine of the trial: ode (the validator of every study) or "
                           "mujoco (the nominal trial replayed in MuJoCo with the same controller "
                           "and judgement; docs/mujoco.md)"),
                  {"ode", "mujoco"}),
      [ref](R& r) -> std::string& { return ref(r).engine; }));
  list->push_back(FieldOption<R>(
      WithChoices(MakeInfo("mujoco_servo", OptionKind::kText,
                           "MuJoCo's finger servos: stiff (the force cap reached at 0.01 rad/s of "
                           "velocity error) or soft (at 0.5 rad/s); docs/mujoco.md"),
                  {"stiff", "soft"}),
      [ref](R& r) -> std::string& { return ref(r).mujoco_servo; }));
}

/// The options of ExportMjcfRequest, in the order the front ends list them.
const OptionList<ExportMjcfRequest>& ExportMjcfOptions();

/// The model's options of `request`. Throws InputError for invalid ones.
MjcfOptions ToMjcfOptions(const ExportMjcfRequest& request);

/// The MuJoCo trial's options of `settings` with the trial's step `time_step` (s; 0: 1 ms).
/// Throws InputError for invalid ones.
MujocoTrialOptions ToMujocoTrialOptions(const EngineSettings& settings, double time_step);

}  // namespace graspsynth::request
