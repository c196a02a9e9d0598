#include "request/analyze_request.hpp"

#include <utility>

#include "common/valid_options.hpp"

namespace graspsynth::request {
namespace {

using R = AnalyzeRequest;

// success_lift of request type Q, reading and writing the number `ref` returns.
template <class Q, class F>
Option<Q> SuccessLiftOption(F ref) {
  return FieldOption<Q>(WithRange(MakeInfo("success_lift", OptionKind::kNumber,
                                           "Lift in metres that makes a trial successful"),
                                  0.0),
                        ref);
}

// robust_loss and loss_scale of request type Q, reading and writing the fields of `loss` and
// `scale`.
template <class Q, class FL, class FS>
void AppendLineLossOptions(FL loss, FS scale, OptionList<Q>* list) {
  list->push_back(FieldOption<Q>(
      WithChoices(MakeInfo("robust_loss", OptionKind::kText, "Robust loss of the wrist-line fit"),
                  {"none", "huber", "cauchy"}),
      loss));
  list->push_back(FieldOption<Q>(
      WithRange(MakeInfo("loss_scale", OptionKind::kNumber,
                         "Scale of the robust loss in metres (residual where it turns over)"),
                0.0, INFINITY, true),
      scale));
}

LineLoss LineLossOf(const std::string& text) {
  return text == "huber"    ? LineLoss::kHuber
         : text == "cauchy" ? LineLoss::kCauchy
                            : LineLoss::kNone;
}

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
  list.push_back(SuccessLiftOption<R>([](R& r) -> double& { return r.success_lift; }));
  AppendLineLossOptions<R>([](R& r) -> std::string& { return r.robust_loss; },
                           [](R& r) -> double& { return r.loss_scale; }, &list);
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
  options.line.loss = LineLossOf(request.robust_loss);
  options.line.loss_scale = request.loss_scale;
  options.line_points =
      request.line_points == "trials" ? LinePoints::kTrials : LinePoints::kOrientationMeans;
  RequireValid(options, "analyze");
  return options;
}

const OptionList<SegmentRequest>& SegmentOptions() {
  static const OptionList<SegmentRequest> options = [] {
    OptionList<SegmentRequest> list;
    list.push_back(SuccessLiftOption<SegmentRequest>(
        [](SegmentRequest& r) -> double& { return r.success_lift; }));
    return list;
  }();
  return options;
}

const OptionList<WristLineRequest>& WristLineRequestOptions() {
  static const OptionList<WristLineRequest> options = [] {
    using Q = WristLineRequest;
    OptionList<Q> list;
    AppendLineLossOptions<Q>([](Q& r) -> std::string& { return r.robust_loss; },
                             [](Q& r) -> double& { return r.loss_scale; }, &list);
    return list;
  }();
  return options;
}

SegmentationOptions ToSegmentationOptions(const SegmentRequest& request,
                                          const GraspRegionModel& region) {
  SegmentationOptions options;
  options.region = region;
  options.success_lift = request.success_lift;
  RequireValid(options, "segmentation");
  return options;
}

WristLineOptions ToWristLineOptions(const WristLineRequest& request) {
  WristLineOptions options;
  options.loss = LineLossOf(request.robust_loss);
  options.loss_scale = request.loss_scale;
  RequireValid(options, "wrist-line fit");
  return options;
}

}  // namespace graspsynth::request
