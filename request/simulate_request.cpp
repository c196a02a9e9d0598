#include "request/simulate_request.hpp"

#include <algorithm>
#include <utility>

#include "common/valid_options.hpp"
#include "request/hold_margin_options.hpp"
#include "request/physics_options.hpp"

namespace graspsynth::request {
namespace {

// The trial's settings of request type R (fidelity, time_step, hold), through `ref`.
template <class R, class F>
void AppendTrialSettings(F ref, OptionList<R>* list) {
  list->push_back(FieldOption<R>(
      WithChoices(MakeInfo("fidelity", OptionKind::kText,
                           "fast: kinematic arm, free space without contact detail, 4 ms steps, "
                           "early stop; fast-wrist: fast with the wrist joints (E2, W1, W2) "
                           "dynamic, so that their 10-15 N m motors yield; full: dynamic "
                           "motor-driven arm, every step simulated at 1 ms"),
                  {"fast", "fast-wrist", "full"}),
      [ref](R& r) -> std::string& { return ref(r).fidelity; }));
  list->push_back(FieldOption<R>(
      MakeInfo("time_step", OptionKind::kNumber, "Physics step in s (0: the fidelity's default)"),
      [ref](R& r) -> double& { return ref(r).time_step; }));
  list->push_back(FieldOption<R>(MakeInfo("hold", OptionKind::kNumber,
                                          "Seconds the last command is held after the trajectory"),
                                 [ref](R& r) -> double& { return ref(r).hold; }));
}

template <class R>
Option<R> SeedOption(const char* help, uint64_t R::*field) {
  return FieldOption<R>(MakeInfo("seed", OptionKind::kUnsigned, help),
                        [field](R& r) -> uint64_t& { return r.*field; });
}

template <class R>
Option<R> ThreadsOption(const char* help, int R::*field) {
  return FieldOption<R>(ThreadsInfo(help), [field](R& r) -> int& { return r.*field; });
}

template <class R>
Option<R> NumberOption(OptionInfo info, double R::*field) {
  return FieldOption<R>(std::move(info), [field](R& r) -> double& { return r.*field; });
}

OptionList<SimulateRequest> MakeSimulateOptions() {
  using R = SimulateRequest;
  OptionList<R> list;
  list.push_back(
      AtOption<R>("X,Y: play it with the object centre here on the table (world, m) "
                  "instead of where the file puts it (its \"object_xy\", else the "
                  "scene's object centre)",
                  [](R& r) -> std::optional<Eigen::Vector2d>& { return r.at; }));
  list.push_back(FieldOption<R>(WithRange(MakeInfo("perturb", OptionKind::kInt,
                                                   "Number of perturbed replays (0: nominal only)"),
                                          0),
                                [](R& r) -> int& { return r.perturb; }));
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("sensitivity", OptionKind::kInt,
                         "Replays per end of each physics factor's range, that factor alone "
                         "varied (0: no sensitivity table)"),
                0),
      [](R& r) -> int& { return r.sensitivity; }));
  list.push_back(SeedOption("Seed of the perturbations", &R::seed));
  list.push_back(ThreadsOption("Worker threads for the replays (0: all cores)", &R::threads));
  list.push_back(
      NumberOption(WithRange(MakeInfo("record_interval", OptionKind::kNumber,
                                      "Seconds between recorded states (--record, --trial-record)"),
                             0.0, INFINITY, true),
                   &R::record_interval));
  AppendTrialSettings<R>([](R& r) -> TrialSettings& { return r.trial; }, &list);
  AppendEngineOptions<R>([](R& r) -> EngineSettings& { return r.engine; }, &list);
  list.push_back(NumberOption(
      MakeInfo("time_scale_min", OptionKind::kNumber, "Smallest time scale of a replay"),
      &R::time_scale_min));
  list.push_back(NumberOption(
      MakeInfo("time_scale_max", OptionKind::kNumber, "Largest time scale of a replay"),
      &R::time_scale_max));
  list.push_back(NumberOption(MakeInfo("position_noise", OptionKind::kNumber,
                                       "Wrist position noise, m (standard deviation per axis)"),
                              &R::position_noise));
  list.push_back(
      NumberOption(MakeInfo("orientation_noise", OptionKind::kNumber,
                            "Wrist orientation noise, deg (standard deviation per axis)"),
                   &R::orientation_noise_deg));
  list.push_back(NumberOption(MakeInfo("finger_noise", OptionKind::kNumber,
                                       "Finger joint noise, deg (standard deviation per joint)"),
                              &R::finger_noise_deg));
  AppendPhysicsOptions<R>([](R& r) -> PhysicsPerturbationOptions& { return r.physics; }, &list);
  AppendHoldMarginOptions<R>([](R& r) -> HoldMarginOptions& { return r.hold_margin; }, &list);
  return list;
}

OptionList<TrialRequest> MakeTrialOptions() {
  using R = TrialRequest;
  OptionList<R> list;
  AppendTrialSettings<R>([](R& r) -> TrialSettings& { return r.trial; }, &list);
  list.push_back(
      NumberOption(WithRange(MakeInfo("record_interval", OptionKind::kNumber,
                                      "Seconds between recorded states (0: none recorded)"),
                             0.0),
                   &R::record_interval));
  return list;
}

OptionList<RobustnessRequest> MakeRobustnessOptions() {
  using R = RobustnessRequest;
  OptionList<R> list;
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("trials", OptionKind::kInt, "Number of perturbed replays"), 1),
      [](R& r) -> int& { return r.trials; }));
  list.push_back(SeedOption("Seed of the perturbations", &R::seed));
  list.push_back(ThreadsOption("Worker threads for the replays (0: all cores); changes no result",
                               &R::threads));
  list.push_back(NumberOption(
      WithRange(MakeInfo("noise_scale", OptionKind::kNumber,
                         "Factor on the replays' wrist position, orientation and finger noise "
                         "(5 mm, 2 deg, 2 deg)"),
                0.0),
      &R::noise_scale));
  AppendTrialSettings<R>([](R& r) -> TrialSettings& { return r.trial; }, &list);
  AppendPhysicsOptions<R>([](R& r) -> PhysicsPerturbationOptions& { return r.physics; }, &list);
  return list;
}

OptionList<ScriptedGraspRequest> MakeScriptedGraspOptions() {
  using R = ScriptedGraspRequest;
  OptionList<R> list;
  list.push_back(
      NumberOption(MakeInfo("theta", OptionKind::kNumber, "Object orientation, deg"), &R::theta));
  list.push_back(
      NumberOption(WithRange(MakeInfo("grasp_radius", OptionKind::kNumber,
                                      "Grasp point along the handle from the object centre, m"),
                             0.0, INFINITY, true),
                   &R::grasp_radius));
  list.push_back(FieldOption<R>(
      MakeInfo("keep_open", OptionKind::kBool, "Keep the hand open (a trajectory that must fail)"),
      [](R& r) -> bool& { return r.keep_open; }));
  return list;
}

}  // namespace

const OptionList<ScriptedGraspRequest>& ScriptedGraspRequestOptions() {
  static const OptionList<ScriptedGraspRequest> options = MakeScriptedGraspOptions();
  return options;
}

ScriptedGraspOptions ToScriptedGraspOptions(const ScriptedGraspRequest& request) {
  ScriptedGraspOptions g;
  g.theta_deg = request.theta;
  g.grasp_radius = request.grasp_radius;
  g.keep_open = request.keep_open;
  RequireValid(g, "bad scripted grasp option");
  return g;
}

const OptionList<SimulateRequest>& SimulateOptions() {
  static const OptionList<SimulateRequest> options = MakeSimulateOptions();
  return options;
}

const OptionList<TrialRequest>& TrialRequestOptions() {
  static const OptionList<TrialRequest> options = MakeTrialOptions();
  return options;
}

const OptionList<RobustnessRequest>& RobustnessRequestOptions() {
  static const OptionList<RobustnessRequest> options = MakeRobustnessOptions();
  return options;
}

TrialOptions ToTrialOptions(const TrialSettings& settings) {
  TrialOptions trial;
  trial.fidelity = settings.fidelity == "full"         ? Fidelity::kFull
                   : settings.fidelity == "fast-wrist" ? Fidelity::kFastWristDynamic
                                                       : Fidelity::kFast;
  trial.time_step = settings.time_step;
  trial.hold = settings.hold;
  RequireValid(trial, "bad simulation option");
  return trial;
}

TrialOptions ToTrialOptions(const TrialRequest& request) {
  TrialOptions trial = ToTrialOptions(request.trial);
  trial.record_interval = request.record_interval;
  RequireValid(trial, "bad simulation option");
  return trial;
}

TrialOptions ToTrialOptions(const SimulateRequest& request) {
  return ToTrialOptions(request.trial);
}

RobustnessOptions ToRobustnessOptions(const SimulateRequest& request) {
  RobustnessOptions ro;
  ro.trials = std::max(request.perturb, 1);
  ro.seed = request.seed;
  ro.threads = request.threads;
  ro.trial = ToTrialOptions(request);
  ro.perturbation.time_scale_min = request.time_scale_min;
  ro.perturbation.time_scale_max = request.time_scale_max;
  ro.perturbation.position_sigma = request.position_noise;
  ro.perturbation.orientation_sigma = request.orientation_noise_deg * kDeg;
  ro.perturbation.finger_sigma = request.finger_noise_deg * kDeg;
  ro.perturbation.physics = request.physics;
  RequireValid(ro, "bad perturbation option");
  return ro;
}

RobustnessOptions ToRobustnessOptions(const RobustnessRequest& request) {
  RobustnessOptions ro;
  ro.trials = request.trials;
  ro.seed = request.seed;
  ro.threads = request.threads;
  ro.trial = ToTrialOptions(request.trial);
  ro.perturbation.ScaleMotionNoise(request.noise_scale);
  ro.perturbation.physics = request.physics;
  RequireValid(ro, "bad perturbation option");
  return ro;
}

}  // namespace graspsynth::request
