#include "request/synthesize_request.hpp"

#include <utility>

#include "request/hold_margin_options.hpp"
#include "request/mujoco_request.hpp"
#include "request/physics_options.hpp"
#include "solver/reach_planning.hpp"

#include "common/valid_options.hpp"

namespace graspsynth::request {
namespace {

using R = SynthesizeRequest;

OptionInfo Placeholder(OptionInfo info, const char* placeholder) {
  info.placeholder = placeholder;
  return info;
}

OptionList<R> MakeOptions() {
  OptionList<R> list;
  OptionInfo theta = MakeInfo("theta", OptionKind::kNumber, "Object orientation, degrees");
  theta.required = true;
  list.push_back(FieldOption<R>(theta, [](R& r) -> double& { return r.theta; }));
  list.push_back(
      AtOption<R>("X,Y: the object centre on the table, world frame, metres (e.g. -0.30,0.90); "
                  "default: the scene's object centre (the paper's fixed position)",
                  [](R& r) -> std::optional<Eigen::Vector2d>& { return r.at; }));
  OptionInfo method = MakeInfo("method", OptionKind::kText, "interp, line or nearest");
  method.choices = {"interp", "line", "nearest"};
  list.push_back(FieldOption<R>(method, [](R& r) -> std::string& { return r.method; }));
  list.push_back(FieldOption<R>(
      MakeInfo("refine", OptionKind::kBool, "The Ceres and NLopt refinement of the motion"),
      [](R& r) -> bool& { return r.refine; }));
  OptionInfo reach =
      MakeInfo("reach", OptionKind::kText,
               "spline (the paper's Cartesian spline), joint (minimum-jerk joint move "
               "to the pre-grasp configuration) or auto (the spline unless it passes "
               "within 1 cm of the workspace's edge)");
  reach.choices = {"spline", "joint", "auto"};
  list.push_back(FieldOption<R>(reach, [](R& r) -> std::string& { return r.reach; }));
  list.push_back(FieldOption<R>(
      MakeInfo("clearance_margin", OptionKind::kNumber,
               "The refinement's clearance of hand and arm from object and table along the "
               "approach, m"),
      [](R& r) -> double& { return r.clearance_margin; }));
  list.push_back(FieldOption<R>(
      MakeInfo("strict_thresholds", OptionKind::kBool,
               "Refine to the default clearance, penetration and contact thresholds even where the "
               "source demonstrations, which held the object in physics, break them"),
      [](R& r) -> bool& { return r.strict_thresholds; }));
  list.push_back(FieldOption<R>(
      MakeInfo(
          "grip_slide", OptionKind::kBool,
          "After the refinement, slide a grasp that holds the handle within 4 cm of its end in "
          "toward the object's centre (by up to 5 cm, then half and a quarter of it; the first "
          "that keeps the refinement's constraints and 2 cm between arm and object is kept; a "
          "slid grip whose nominal trial fails gives way to the unslid one)"),
      [](R& r) -> bool& { return r.grip_slide; }));
  list.push_back(OptionalVectorOption<R, kArmDof>(
      Placeholder(MakeInfo("start", OptionKind::kNumbers,
                           "Start arm configuration q1,...,q7, radians (default: the rest pose for "
                           "the grasp orientation)"),
                  "Q1,...,Q7"),
      [](R& r) -> std::optional<Vector7d>& { return r.start; }));
  list.push_back(
      FieldOption<R>(MakeInfo("seed", OptionKind::kUnsigned, "Seed of the perturbed trials"),
                     [](R& r) -> uint64_t& { return r.gate.robustness.seed; }));
  OptionInfo perturb = MakeInfo("perturb", OptionKind::kInt,
                                "Perturbed trials of the physics gate (0: nominal only)");
  perturb.lo = 0;
  list.push_back(FieldOption<R>(perturb, [](R& r) -> int& { return r.gate.robustness.trials; }));
  list.push_back(FieldOption<R>(ThreadsInfo("Worker threads of the gate (0: all cores)"),
                                [](R& r) -> int& { return r.gate.robustness.threads; }));
  OptionInfo robustness = MakeInfo("min_robustness", OptionKind::kNumber,
                                   "Success fraction the gate needs under perturbation");
  robustness.lo = 0.0;
  robustness.hi = 1.0;
  list.push_back(FieldOption<R>(robustness, [](R& r) -> double& { return r.gate.min_robustness; }));
  list.push_back(PhysicsFallbackOption<R>([](R& r) -> bool& { return r.physics_fallback; }));
  AppendPhysicsOptions<R>(
      [](R& r) -> PhysicsPerturbationOptions& { return r.gate.robustness.perturbation.physics; },
      &list);
  AppendGateEngineOptions<R>([](R& r) -> MujocoGateOptions& { return r.gate.mujoco; }, &list);
  AppendHoldMarginOptions<R>([](R& r) -> HoldMarginOptions& { return r.gate.hold_margin; }, &list);
  return list;
}

}  // namespace

const OptionList<SynthesizeRequest>& SynthesizeOptions() {
  static const OptionList<SynthesizeRequest> options = MakeOptions();
  return options;
}

ValidatedSynthesisOptions ToValidatedSynthesisOptions(const SynthesizeRequest& request) {
  ValidatedSynthesisOptions vo;
  SynthesisOptions& so = vo.synthesis;
  so.generation.method = ParseSynthesisMethod(request.method);
  if (!request.refine) so.refinement_stages.clear();
  so.reach.method = ParseReachMethod(request.reach);
  so.refinement.clearance_margin = request.clearance_margin;
  if (request.strict_thresholds) so.source_thresholds.reset();
  if (request.grip_slide) {
    if (!request.refine)
      throw InputError(
          "grip_slide needs the refinement (refine on; on the command line, drop --no-refine)");
    so.grip_slide = GripSlideOptions{};
  }
  so.start = request.start;
  vo.physics_fallback = request.physics_fallback;
  vo.gate = request.gate;
  RequireValid(so, "bad synthesis option");
  RequireValid(vo.gate, "bad physics gate option");
  RequireGateEngines(vo.gate.mujoco);
  return vo;
}

}  // namespace graspsynth::request
