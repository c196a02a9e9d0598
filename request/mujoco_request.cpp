#include "request/mujoco_request.hpp"

#include "common/errors.hpp"
#include "common/valid_options.hpp"
#include "simulation_mujoco/mujoco_world.hpp"

namespace graspsynth::request {
namespace {

OptionList<ExportMjcfRequest> MakeExportMjcfOptions() {
  using R = ExportMjcfRequest;
  OptionList<R> list;
  list.push_back(
      OptionalFieldOption<R>(MakeInfo("theta", OptionKind::kNumber,
                                      "Object orientation, deg (none: the trajectory's, else 0)"),
                             [](R& r) -> std::optional<double>& { return r.theta; }));
  list.push_back(
      AtOption<R>("X,Y: the object centre on the table (world, m) instead of the "
                  "trajectory's (its \"object_xy\") or the scene's object centre",
                  [](R& r) -> std::optional<Eigen::Vector2d>& { return r.at; }));
  list.push_back(FieldOption<R>(
      WithChoices(MakeInfo("mujoco_servo", OptionKind::kText,
                           "The finger servos' gain: stiff (force cap at 0.01 rad/s of velocity "
                           "error) or soft (at 0.5 rad/s); docs/mujoco.md"),
                  {"stiff", "soft"}),
      [](R& r) -> std::string& { return r.mujoco_servo; }));
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("time_step", OptionKind::kNumber, "MuJoCo's physics step, s"), 0.0, 0.02,
                true),
      [](R& r) -> double& { return r.time_step; }));
  return list;
}

}  // namespace

const OptionList<ExportMjcfRequest>& ExportMjcfOptions() {
  static const OptionList<ExportMjcfRequest> options = MakeExportMjcfOptions();
  return options;
}

MjcfOptions ToMjcfOptions(const ExportMjcfRequest& request) {
  MjcfOptions o;
  o.time_step = request.time_step;
  o.servo = ParseMujocoServo(request.mujoco_servo, "--mujoco-servo");
  RequireValid(o, "bad MJCF option");
  return o;
}

MujocoTrialOptions ToMujocoTrialOptions(const EngineSettings& settings, double time_step) {
  MujocoTrialOptions o;
  o.time_step = time_step;
  o.servo = ParseMujocoServo(settings.mujoco_servo, "--mujoco-servo");
  RequireValid(o, "bad MuJoCo option");
  return o;
}

void RequireGateEngines(const MujocoGateOptions& gate) {
  if (gate.enabled && !MujocoAvailable()) {
    throw InputError(
        "--engines ode,mujoco: this graspsynth is built without MuJoCo (install libmujoco-dev, "
        "or run scripts/setup.sh, and build again)");
  }
}

}  // namespace graspsynth::request
