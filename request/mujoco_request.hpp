#pragma once

/// @file
/// The MuJoCo engine's requests (docs/mujoco.md): `graspsynth export-mjcf`'s (ExportMjcfRequest)
/// and the engine settings of `graspsynth simulate` (SimulateRequest's engine and
/// mujoco_servo, described here once). The trajectory, robot, scene and object are not options,
/// nor is the output file.

#include <optional>
#include <string>

#include <Eigen/Core>

#include "gate/physics_gate.hpp"
#include "request/option.hpp"
#include "simulation_mujoco/mjcf_export.hpp"
#include "simulation_mujoco/mujoco_trial.hpp"

namespace graspsynth::request {

/// The physics engine of a simulation request and the MuJoCo servo mapping.
struct EngineSettings {
  std::string engine = "ode";          ///< ode or mujoco
  std::string mujoco_servo = "stiff";  ///< stiff or soft (MujocoServo)
  /// With engine mujoco: the contact settings' sweep (simulation_mujoco/mujoco_sweep.hpp, both
  /// servo mappings) instead of the one trial.
  bool mujoco_sweep = false;
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
  list->push_back(FieldOption<R>(
      MakeInfo("mujoco_sweep", OptionKind::kBool,
               "With --engine mujoco: replay the trial under each of MuJoCo's 8 contact settings "
               "with both servo mappings (16 runs; simulation_mujoco/mujoco_sweep.hpp) and "
               "tabulate them"),
      [ref](R& r) -> bool& { return ref(r).mujoco_sweep; }));
}

/// The gate's engine options of request type R through `ref`, which returns the request's
/// MujocoGateOptions (`[](R& r) -> MujocoGateOptions& { return r.gate.mujoco; }`): engines
/// (ode or ode,mujoco, read and written as MujocoGateOptions::enabled) and mujoco_min_success.
template <class R, class F>
void AppendGateEngineOptions(F ref, OptionList<R>* list) {
  Option<R> engines;
  engines.info =
      WithChoices(MakeInfo("engines", OptionKind::kText,
                           "The physics gate's engines: ode (the validator) or ode,mujoco (a grasp "
                           "must also hold in MuJoCo under its 8 contact settings with both servo "
                           "mappings; docs/mujoco.md)"),
                  {"ode", "ode,mujoco"});
  engines.get = [ref](const R& r) -> Value {
    return std::string(ref(const_cast<R&>(r)).enabled ? "ode,mujoco" : "ode");
  };
  engines.set = [ref](R& r, const Value& v) {
    ref(r).enabled = std::get<std::string>(v) == "ode,mujoco";
  };
  list->push_back(std::move(engines));
  list->push_back(FieldOption<R>(
      WithRange(MakeInfo("mujoco_min_success", OptionKind::kNumber,
                         "With --engines ode,mujoco: the share of MuJoCo's 16 runs that must "
                         "hold (0.95: every one)"),
                0.0, 1.0),
      [ref](R& r) -> double& { return ref(r).min_success; }));
}

/// Throws InputError when `gate` asks for MuJoCo and this build has none (the command then
/// exits with status 2).
void RequireGateEngines(const MujocoGateOptions& gate);

/// The options of ExportMjcfRequest, in the order the front ends list them.
const OptionList<ExportMjcfRequest>& ExportMjcfOptions();

/// The model's options of `request`. Throws InputError for invalid ones.
MjcfOptions ToMjcfOptions(const ExportMjcfRequest& request);

/// The MuJoCo trial's options of `settings` with the trial's step `time_step` (s; 0: 1 ms).
/// Throws InputError for invalid ones.
MujocoTrialOptions ToMujocoTrialOptions(const EngineSettings& settings, double time_step);

}  // namespace graspsynth::request
