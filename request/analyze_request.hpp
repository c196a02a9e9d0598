#pragma once

/// @file
/// The request of `graspsynth analyze` and of Python's analyze_demonstrations: Table I, the
/// wrist line and the radial model of a folder of demonstrations. Its options are described
/// once (AnalyzeOptions) and turned into the library's options once (ToAnalysisOptions), for
/// both front ends. The folder, scene and object are not options, nor are the command's output
/// files and its gnuplot program.

#include <string>

#include "analysis/analysis_report.hpp"
#include "request/option.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth::request {

/// How to segment the demonstrations and fit the wrist line; the defaults are the library's,
/// and the grasp region's are the scene's.
struct AnalyzeRequest {
  std::string region;          ///< cylinder or sphere; empty: the scene's shape
  double region_radius = 0.0;  ///< m; 0: the scene's
  double region_height = 0.0;  ///< m, the cylinder's; 0: the scene's
  double success_lift = SegmentationOptions{}.success_lift;  ///< m
  std::string robust_loss = "none";                          ///< none, huber or cauchy
  double loss_scale = WristLineOptions{}.loss_scale;         ///< m
  std::string line_points = "means";                         ///< means or trials
};

/// The options of AnalyzeRequest, in the order the front ends list them.
const OptionList<AnalyzeRequest>& AnalyzeOptions();

/// The request of Python's segment: analyze's segmentation option (the region is the scene's).
struct SegmentRequest {
  double success_lift = SegmentationOptions{}.success_lift;  ///< m
};

/// The options of SegmentRequest (analyze's success_lift).
const OptionList<SegmentRequest>& SegmentOptions();

/// The request of Python's fit_wrist_line: analyze's options of the wrist-line fit.
struct WristLineRequest {
  std::string robust_loss = "none";                   ///< none, huber or cauchy
  double loss_scale = WristLineOptions{}.loss_scale;  ///< m
};

/// The options of WristLineRequest (analyze's robust_loss and loss_scale).
const OptionList<WristLineRequest>& WristLineRequestOptions();

/// The library's options of `request` over the grasp region `region`. Throws InputError.
SegmentationOptions ToSegmentationOptions(const SegmentRequest& request,
                                          const GraspRegionModel& region);

/// The library's options of `request`. Throws InputError "wrist-line fit: ...".
WristLineOptions ToWristLineOptions(const WristLineRequest& request);

/// The library's options of `request` over the grasp region `scene_region` (the scene's).
/// Throws InputError "analyze: ..." for an invalid combination.
AnalysisOptions ToAnalysisOptions(const AnalyzeRequest& request,
                                  const GraspRegionModel& scene_region);

}  // namespace graspsynth::request
