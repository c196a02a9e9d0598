#include "request/generalize_request.hpp"

#include <utility>

#include "common/orientation_list.hpp"
#include "request/hold_margin_options.hpp"
#include "request/mujoco_request.hpp"
#include "request/physics_options.hpp"
#include "studies/study_method.hpp"

namespace graspsynth::request {
namespace {

using R = GeneralizeRequest;

// Throws InputError naming `where` unless every label names a study method, once.
void CheckMethods(const Value& value, const std::string& where) {
  std::vector<std::string> seen;
  for (const std::string& label : std::get<std::vector<std::string>>(value)) {
    try {
      seen.push_back(ParseStudyMethod(label).Label());
    } catch (const InputError& e) {
      throw InputError(where + ": " + e.what());
    }
    for (size_t k = 0; k + 1 < seen.size(); ++k) {
      if (seen[k] == seen.back()) throw InputError(where + ": '" + label + "' is given twice");
    }
  }
}

OptionList<R> MakeOptions() {
  OptionList<R> list;
  list.push_back(
      NumberListOption<R>("orientations", "degrees",
                          "Orientations, deg: numbers and ranges FROM:TO:STEP, comma-separated",
                          [](R& r) -> std::string& { return r.orientations; }));
  AppendPositionListOptions<R>(
      "Object positions: x of the object centre on the table, m, numbers and ranges "
      "FROM:TO:STEP (with y: every orientation at every x at every y); default: the scene's "
      "object centre",
      [](R& r) -> std::string& { return r.x; }, [](R& r) -> std::string& { return r.y; }, &list);
  Option<R> o =
      FieldOption<R>(MakeInfo("methods", OptionKind::kTextList, "Comma-separated methods"),
                     [](R& r) -> std::vector<std::string>& { return r.methods; });
  o.check = CheckMethods;
  list.push_back(std::move(o));
  list.push_back(FieldOption<R>(
      MakeInfo("leave_one_out", OptionKind::kBool,
               "Synthesize each inner library orientation from the library without it "
               "(orientations is not used)"),
      [](R& r) -> bool& { return r.leave_one_out; }));
  OptionInfo perturb =
      MakeInfo("perturb", OptionKind::kInt, "Perturbed replays per grasp (0: nominal only)");
  perturb.lo = 0;
  list.push_back(FieldOption<R>(perturb, [](R& r) -> int& { return r.perturb; }));
  OptionInfo sensitivity =
      MakeInfo("sensitivity", OptionKind::kInt,
               "Replays per end of each physics factor's range in each grasp's "
               "sensitivity table (0: none)");
  sensitivity.lo = 0;
  list.push_back(FieldOption<R>(sensitivity, [](R& r) -> int& { return r.sensitivity; }));
  OptionInfo noise = MakeInfo("noise_scale", OptionKind::kNumber,
                              "Factor on the replays' wrist position, orientation and finger noise "
                              "(5 mm, 2 deg, 2 deg)");
  noise.lo = 0.0;
  list.push_back(FieldOption<R>(noise, [](R& r) -> double& { return r.noise_scale; }));
  list.push_back(
      FieldOption<R>(MakeInfo("seed", OptionKind::kUnsigned, "Seed of the perturbed replays"),
                     [](R& r) -> uint64_t& { return r.seed; }));
  list.push_back(FieldOption<R>(ThreadsInfo("Worker threads (0: all cores); changes no result"),
                                [](R& r) -> int& { return r.threads; }));
  list.push_back(PhysicsFallbackOption<R>([](R& r) -> bool& { return r.physics_fallback; }));
  AppendPhysicsOptions<R>([](R& r) -> PhysicsPerturbationOptions& { return r.physics; }, &list);
  AppendGateEngineOptions<R>([](R& r) -> MujocoGateOptions& { return r.mujoco; }, &list);
  AppendHoldMarginOptions<R>([](R& r) -> HoldMarginOptions& { return r.hold_margin; }, &list);
  return list;
}

}  // namespace

const OptionList<GeneralizeRequest>& GeneralizeOptions() {
  static const OptionList<GeneralizeRequest> options = MakeOptions();
  return options;
}

SynthesisTableOptions ToSynthesisTableOptions(const GeneralizeRequest& request) {
  SynthesisTableOptions table;
  for (const std::string& label : request.methods) table.methods.push_back(ParseStudyMethod(label));
  table.gate.robustness.trials = request.perturb;
  table.gate.sensitivity_trials = request.sensitivity;
  table.seed = request.seed;
  table.threads = request.threads;
  table.physics_fallback = request.physics_fallback;
  table.gate.hold_margin = request.hold_margin;
  PerturbationOptions& perturbation = table.gate.robustness.perturbation;
  perturbation.ScaleMotionNoise(request.noise_scale);
  perturbation.physics = request.physics;
  std::string why;
  if (!perturbation.IsValid(&why)) throw InputError("noise_scale: " + why);
  table.gate.mujoco = request.mujoco;
  if (!table.gate.mujoco.IsValid(&why)) throw InputError("engines: " + why);
  RequireGateEngines(table.gate.mujoco);
  if (request.leave_one_out) {
    if (!request.x.empty() || !request.y.empty()) {
      throw InputError(
          "leave_one_out works over the library's orientations at its own positions: it takes "
          "no x or y");
    }
  } else {
    table.orientations = ParseOrientationList(request.orientations, "orientations");
    table.positions = ParsePositionGrid(request.x, request.y, "x", "y");
  }
  return table;
}

}  // namespace graspsynth::request
