#include "request/demos_request.hpp"

#include <utility>

#include "common/orientation_list.hpp"
#include "common/valid_options.hpp"

namespace graspsynth::request {
namespace {

using R = DemosRequest;

// The options generate and calibrate share: the seed, the trial count, the threads.
OptionList<R> CommonOptions() {
  OptionList<R> list;
  list.push_back(OptionalFieldOption<R>(
      MakeInfo("seed", OptionKind::kUnsigned, "Seed (default: the operator file's)"),
      [](R& r) -> std::optional<uint64_t>& { return r.seed; }));
  list.push_back(OptionalFieldOption<R>(
      WithRange(MakeInfo("trials_per_orientation", OptionKind::kInt,
                         "Trials at every orientation (default: the operator file's, which may "
                         "differ per orientation)"),
                1),
      [](R& r) -> std::optional<int>& { return r.trials_per_orientation; }));
  list.push_back(
      FieldOption<R>(ThreadsInfo("Worker threads (0: all cores); the output does not depend on it"),
                     [](R& r) -> int& { return r.threads; }));
  return list;
}

OptionList<R> MakeGenerateOptions() {
  OptionList<R> list = CommonOptions();
  AppendPositionListOptions<R>(
      "Object positions: x of the object centre on the table, m, a list or FROM:TO:STEP (with "
      "y: every x at every y); default: the operator file's positions, else the scene's object "
      "centre",
      [](R& r) -> std::string& { return r.x; }, [](R& r) -> std::string& { return r.y; }, &list);
  return list;
}

OptionList<R> MakeCalibrateOptions() {
  OptionList<R> list = CommonOptions();
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("iterations", OptionKind::kInt, "Generate-and-correct rounds"), 1),
      [](R& r) -> int& { return r.iterations; }));
  list.push_back(
      FieldOption<R>(WithRange(MakeInfo("damping", OptionKind::kNumber,
                                        "Fraction of the difference corrected per round"),
                               0.05, 1.0),
                     [](R& r) -> double& { return r.damping; }));
  return list;
}

}  // namespace

const OptionList<DemosRequest>& DemosGenerateOptions() {
  static const OptionList<DemosRequest> options = MakeGenerateOptions();
  return options;
}

const OptionList<DemosRequest>& DemosCalibrateOptions() {
  static const OptionList<DemosRequest> options = MakeCalibrateOptions();
  return options;
}

OperatorOptions ApplyToOperator(const DemosRequest& request, OperatorOptions options) {
  if (request.seed) options.seed = *request.seed;
  if (request.trials_per_orientation) {  // the same count everywhere
    options.trials_per_orientation = *request.trials_per_orientation;
    for (OrientationPlan& plan : options.plans) plan.trials = 0;
  }
  if (!request.x.empty() || !request.y.empty()) {
    options.positions = ParsePositionGrid(request.x, request.y, "--x", "--y");
    RequireValid(options, "--x/--y");
  }
  return options;
}

}  // namespace graspsynth::request
