#include "request/select_request.hpp"

#include "common/valid_options.hpp"
#include "request/physics_options.hpp"

namespace graspsynth::request {
namespace {

using R = SelectRequest;

OptionList<R> MakeOptions() {
  OptionList<R> list;
  OptionInfo perturb =
      MakeInfo("perturb", OptionKind::kInt, "Perturbed replays per demonstration (>= 1)");
  perturb.lo = 1;
  list.push_back(
      FieldOption<R>(perturb, [](R& r) -> int& { return r.selection.robustness.trials; }));
  list.push_back(
      FieldOption<R>(MakeInfo("seed", OptionKind::kUnsigned, "Seed of the perturbations"),
                     [](R& r) -> uint64_t& { return r.selection.robustness.seed; }));
  list.push_back(FieldOption<R>(ThreadsInfo("Worker threads for the replays (0: all cores)"),
                                [](R& r) -> int& { return r.selection.robustness.threads; }));
  list.push_back(AllReplaysOption<R>([](R& r) -> bool& { return r.selection.early_stop; }, true));
  AppendPhysicsOptions<R>(
      [](R& r) -> PhysicsPerturbationOptions& {
        return r.selection.robustness.perturbation.physics;
      },
      &list);
  return list;
}

}  // namespace

const OptionList<SelectRequest>& SelectOptions() {
  static const OptionList<SelectRequest> options = MakeOptions();
  return options;
}

SelectionOptions ToSelectionOptions(const SelectRequest& request, const SceneModel& scene) {
  SelectionOptions options = request.selection;
  options.segmentation.region = scene.grasp_region;
  RequireValid(options, "select");
  return options;
}

}  // namespace graspsynth::request
