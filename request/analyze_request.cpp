#include "request/analyze_request.hpp"

#include <utility>

#include "common/valid_options.hpp"

namespace graspsynth::request {
namespace {

using R = AnalyzeRequest;

OptionList<R> MakeOptions() {
  OptionList<R> list;
  OptionInfo region = MakeInfo("region", OptionKind::kText,
                               "Grasp region shape, cylinder or sphere (default: the scene's, "
                               "cylinder)");
  region.placeholder = "cylinder|sphere";
  Option<R> o = FieldOption<R>(region, [](R& r) -> std::string& { return r.region; });
  o.check = [](const Value& value, const std::string& where) {
    const std::string& text = std::get<std::string>(value);
    if (text != "cylinder" && text != "sphere" && !text.empty()) {
      throw InputError(where + ": '" + text + "' is not one of cylinder, sphere");
    }
  };
  list.push_back(std::move(o));
  list.push_back(
      FieldOption<R>(WithRange(MakeInfo("region_radius", OptionKind::kNumber,
                                        "Grasp region radius in metres (0: the scene's, 0.41)"),
                               0.0),
                     [](R& r) -> double& { return r.region_radius; }));
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("region_height", OptionKind::kNumber,
                         "Cylinder height in metres, centred on the object centre (0: the "
                         "scene's, 1.0)"),
                0.0),
      [](R& r) -> double& { return r.region_height; }));
  list.push_back(FieldOption<R>(WithRange(MakeInfo("success_lift", OptionKind::kNumber,
                                                   "Lift in metres that makes a trial successful"),
                                          0.0),
                                [](R& r) -> double& { return r.success_lift; }));
  list.push_back(FieldOption<R>(
      WithChoices(MakeInfo("robust_loss", OptionKind::kText, "Robust loss of the wrist-line fit"),
                  {"none", "huber", "cauchy"}),
      [](R& r) -> std::string& { return r.robust_loss; }));
  list.push_back(FieldOption<R>(
      WithRange(MakeInfo("loss_scale", OptionKind::kNumber,
                         "Scale of the robust loss in metres (residual where it turns over)"),
                0.0, INFINITY, true),
      [](R& r) -> double& { return r.loss_scale; }));
  list.push_back(FieldOption<R>(
      WithChoices(MakeInfo("line_points", OptionKind::kText,
                           "Fit the wrist line and the radial model to the mean grasp position "
                           "of each orientation (means, as the paper's Fig. 8) or to every "
                           "trial's (trials)"),
                  {"means", "trials"}),
      [](R& r) -> std::string& { return r.line_points; }));
  return list;
}

}  // namespace

const OptionList<AnalyzeRequest>& AnalyzeOptions() {
  static const OptionList<AnalyzeRequest> options = MakeOptions();
  return options;
}

AnalysisOptions ToAnalysisOptions(const AnalyzeRequest& request,
                                  const GraspRegionModel& scene_region) {
  AnalysisOptions options;
  options.segmentation.region = scene_region;
  if (request.region == "cylinder") {
    options.segmentation.region.shape = GraspRegionModel::Shape::kCylinder;
  }
  if (request.region == "sphere") {
    options.segmentation.region.shape = GraspRegionModel::Shape::kSphere;
  }
  if (request.region_radius > 0.0) options.segmentation.region.radius = request.region_radius;
  if (request.region_height > 0.0) options.segmentation.region.height = request.region_height;
  options.segmentation.success_lift = request.success_lift;
  options.line.loss = request.robust_loss == "huber"    ? LineLoss::kHuber
                      : request.robust_loss == "cauchy" ? LineLoss::kCauchy
                                                        : LineLoss::kNone;
  options.line.loss_scale = request.loss_scale;
  options.line_points =
      request.line_points == "trials" ? LinePoints::kTrials : LinePoints::kOrientationMeans;
  RequireValid(options, "analyze");
  return options;
}

}  // namespace graspsynth::request
