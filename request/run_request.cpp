#include "request/run_request.hpp"

#include <utility>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/orientation_list.hpp"
#include "common/valid_options.hpp"
#include "learning_data/demo_directory.hpp"
#include "request/hold_margin_options.hpp"
#include "request/mujoco_request.hpp"
#include "request/physics_options.hpp"

namespace graspsynth::request {
namespace {

using R = RunRequest;

// " (default: the study's N, --quick's M)": what a count left out is.
std::string StudyDefaultText(int StudyOptions::*field) {
  StudyOptions quick;
  quick.UseQuickStudy();
  return " (default: the study's " + std::to_string(StudyOptions{}.*field) + ", --quick's " +
         std::to_string(quick.*field) + ")";
}

// A count that is at least `lo`, or none (the study's default); `field` gives the help the
// defaults.
Option<R> CountOption(const char* name, std::string help, int lo, int StudyOptions::*field,
                      std::optional<int> R::*member) {
  return OptionalFieldOption<R>(
      WithRange(MakeInfo(name, OptionKind::kInt, help + StudyDefaultText(field)), lo),
      [member](R& r) -> std::optional<int>& { return r.*member; });
}

OptionList<R> MakeOptions() {
  OptionList<R> list;
  list.push_back(FieldOption<R>(MakeInfo("seed", OptionKind::kUnsigned, "Seed of the whole study"),
                                [](R& r) -> uint64_t& { return r.seed; }));
  list.push_back(FieldOption<R>(ThreadsInfo("Worker threads (0: all cores); changes no result"),
                                [](R& r) -> int& { return r.threads; }));
  list.push_back(FieldOption<R>(
      MakeInfo("quick", OptionKind::kBool,
               "Reduced study: orientations 40,45,60,85, 2 selection and 3 gate replays"),
      [](R& r) -> bool& { return r.quick; }));
  list.push_back(CountOption("perturb",
                             "Perturbed replays of each synthesized grasp's physics gate", 0,
                             &StudyOptions::gate_perturbations, &R::perturb));
  list.push_back(CountOption("select_perturb",
                             "Perturbed replays per demonstration in the selection, >= 1", 1,
                             &StudyOptions::selection_perturbations, &R::select_perturb));
  list.push_back(CountOption("sensitivity",
                             "Replays per end of each physics factor's range in each synthesized "
                             "grasp's sensitivity table (0: none)",
                             0, &StudyOptions::sensitivity_trials, &R::sensitivity));
  list.push_back(NumberListOption<R>(
      "orientations", "degrees",
      "Comma-separated object orientations to synthesize, deg, each a number or a range "
      "FROM:TO:STEP (default: the study's 20:100:5, --quick's 40,45,60,85)",
      [](R& r) -> std::optional<std::string>& { return r.orientations; }));
  list.push_back(PhysicsFallbackOption<R>([](R& r) -> bool& { return r.physics_fallback; }));
  list.push_back(AllReplaysOption<R>([](R& r) -> bool& { return r.all_replays; }, false));
  AppendPhysicsOptions<R>([](R& r) -> PhysicsPerturbationOptions& { return r.physics; }, &list);
  AppendGateEngineOptions<R>([](R& r) -> MujocoGateOptions& { return r.mujoco; }, &list);
  AppendHoldMarginOptions<R>([](R& r) -> HoldMarginOptions& { return r.hold_margin; }, &list);
  return list;
}

}  // namespace

const OptionList<RunRequest>& RunOptions() {
  static const OptionList<RunRequest> options = MakeOptions();
  return options;
}

StudyOptions ToStudyOptions(const RunRequest& request, const SceneModel& scene,
                            const std::filesystem::path& demos) {
  StudyOptions options;
  options.demos = demos.empty() ? DefaultDemoDirectory(scene.object.name) : demos;
  // the shipped folder is named relative to the project root: the same bytes on every clone.
  if (demos.empty()) options.demos_name = DataRelativeName(options.demos);
  options.seed = request.seed;
  options.threads = request.threads;
  options.analysis.segmentation.region = scene.grasp_region;
  options.paper_object = scene.object.paper_object;
  options.perturbation.physics = request.physics;
  options.physics_fallback = request.physics_fallback;
  options.hold_margin = request.hold_margin;
  options.selection_early_stop = !request.all_replays;
  if (request.quick) options.UseQuickStudy();
  if (request.sensitivity) options.sensitivity_trials = *request.sensitivity;
  if (request.perturb) options.gate_perturbations = *request.perturb;
  if (request.select_perturb) options.selection_perturbations = *request.select_perturb;
  if (request.orientations) {
    options.orientations = ParseOrientationList(*request.orientations, "orientations");
  }
  options.mujoco_gate = request.mujoco;
  RequireValid(options, "run");
  RequireGateEngines(options.mujoco_gate);
  if (!std::filesystem::is_directory(options.demos)) {
    throw InputError("run: demos '" + options.demos.string() + "' is not a folder");
  }
  return options;
}

}  // namespace graspsynth::request
