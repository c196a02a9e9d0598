#pragma once

/// @file
/// The demonstration analysis of the paper's section III-D, end to end: segment every log of a
/// folder, build Table I, fit the wrist line and the radial model, compare with the paper, and
/// write the `graspsynth-analysis/1` report (JSON) and the paper-comparison table (markdown).
///
/// Report format `graspsynth-analysis/1` (object-centred table-plane frame: world x and y axes,
/// origin at the object centre; metres; angles in degrees):
/// - `format`, `directory`, `options` {region {shape, radius_m, height_m}, success_lift_m,
///   line_points ("orientation_means" | "trials"), robust_loss, loss_scale_m};
/// - `counts` {files, rejected, trials, used, unsuccessful, unsegmentable};
/// - `orientations`: [{theta_deg, n, pregrasp {d, eta_deg, x, y, std_d, std_eta_deg, std_x,
///   std_y}, grasp {...the same}, files}] sorted by theta_deg;
/// - `wrist_line` {status, message, point [x, y], direction [dx, dy], angle_deg, offset_m,
///   rms_m, max_m, residuals_m, loss, loss_scale_m, n_points, iterations, plain {point,
///   direction, angle_deg, offset_m, rms_m, max_m}, cgal {point, direction, angle_deg, offset_m,
///   rms_m, max_m, angle_difference_deg, offset_difference_m, agrees}};
/// - `radial_model` {valid, d_m, c_deg, rms_m, max_m, residuals_m} (eta = theta + c, d constant);
/// - `angular_ranges` {object_theta_deg, grasp_eta_deg, pregrasp_eta_deg, grasp_to_object_ratio};
/// - `placement_line` (only when the trials' objects stand at two or more positions; the wrist
///   relative to the object in world axes, not the table frame): {valid, message, model,
///   samples, positions, reference_m [x, y], b_m, a_x, a_y, a_theta_m_per_rad (each [x, y, z]),
///   line_angle_deg, iterations, residuals {rms_xy_m, max_xy_m, rms_z_m, per_sample_m
///   [[x, y, z]...]}, theta_only {...the same}} (placement_line.hpp);
/// - `paper_comparison` {distance_tolerance_m, angle_tolerance_deg, rows [{theta_deg,
///   n_paper, n_ours, paper {...}, ours {...}, difference {...}, within_tolerance, note}]};
/// - `rejected` [{file, reason}] (files the reader rejected), `skipped` [{file, reason}] (trials
///   left out as unsuccessful or unsegmentable).

#include <optional>
#include <string>
#include <vector>

#include "analysis/placement_line.hpp"
#include "analysis/table_analysis.hpp"
#include "analysis/wrist_line.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/segmentation.hpp"

namespace graspsynth {

/// Which positions the wrist line and the radial model are fitted to.
enum class LinePoints {
  kOrientationMeans,  ///< the mean grasp position of each orientation (the paper's Fig. 8)
  kTrials,            ///< every used trial's grasp position
};

/// "orientation_means" or "trials".
const char* ToString(LinePoints points);

/// Inputs of AnalyzeDemonstrations().
struct AnalysisOptions {
  SegmentationOptions segmentation;                        ///< grasp region and success threshold
  WristLineOptions line;                                   ///< the wrist-line fit
  LinePoints line_points = LinePoints::kOrientationMeans;  ///< what the line is fitted to

  /// True when both option sets are valid; otherwise the reason in `why`.
  bool IsValid(std::string* why) const;
};

/// Everything the analysis found.
struct DemonstrationAnalysis {
  std::string directory;                    ///< the folder read
  AnalysisOptions options;                  ///< the options used
  int files = 0;                            ///< logs read without error
  std::vector<RejectedDemoFile> rejected;   ///< files the reader rejected, with reasons
  TableAnalysis table;                      ///< Table I of our data
  std::vector<double> fit_theta;            ///< object orientation of each fitted point, rad
  std::vector<Eigen::Vector2d> fit_points;  ///< the grasp positions fitted, object-centred, m
  WristLineResult line;                     ///< the wrist line
  RadialModelResult radial;                 ///< the radial strategy on the same points
  AngularRanges grasp_ranges;               ///< mean grasp positions' eta range vs the theta range
  AngularRanges pregrasp_ranges;  ///< mean pre-grasp positions' eta range vs the theta range
  /// The line principle over placements (placement_line.hpp), over the successful segmented
  /// trials' grasps (per placement means or trials, as line_points); only when the trials'
  /// objects stand at two or more positions.
  std::optional<PlacementLineFit> placement_line;
};

/// Segments every log of `demos`, builds the table, fits the wrist line and the radial model to
/// the grasp positions chosen by options.line_points (in increasing theta), and computes the
/// angular ranges from the orientation means. Aborts (GS_DEMAND) when `options` is not valid.
DemonstrationAnalysis AnalyzeDemonstrations(const DemoDirectory& demos,
                                            const AnalysisOptions& options);

/// One row of the paper's Table I (our reading of the paper's garbled table).
struct PaperTableRow {
  double theta_deg = 0.0;         ///< object orientation, degrees
  int n = 0;                      ///< number of successful trials averaged
  double pregrasp_d = 0.0;        ///< m
  double pregrasp_eta_deg = 0.0;  ///< degrees
  double grasp_d = 0.0;           ///< m
  double grasp_eta_deg = 0.0;     ///< degrees
};

/// The paper's Table I: theta 20..100 deg in steps of 10.
const std::vector<PaperTableRow>& PaperTableI();

/// Tolerances of the comparison with the paper.
struct PaperComparisonOptions {
  double distance_tolerance = 0.005;  ///< m, on d (pre-grasp and grasp)
  double angle_tolerance_deg = 2.0;   ///< degrees, on eta (pre-grasp and grasp)

  /// True when both tolerances are finite and >= 0.
  bool IsValid(std::string* why) const;
};

/// One orientation of the comparison: the paper's row, ours, and ours minus the paper's.
struct PaperComparisonRow {
  double theta_deg = 0.0;
  std::optional<PaperTableRow> paper;  ///< absent when the paper has no such orientation
  std::optional<PaperTableRow> ours;   ///< absent when our data has no such orientation
  PaperTableRow difference;  ///< ours - paper (eta wrapped to [-180, 180]); zero if one is absent
  bool within_tolerance = false;  ///< both present and every difference within the tolerances
};

/// The rows of the paper's table and of `table`, matched by theta (to 1e-9 deg), in increasing
/// theta. Aborts (GS_DEMAND) when `options` is not valid.
std::vector<PaperComparisonRow> CompareWithPaper(const TableAnalysis& table,
                                                 const PaperComparisonOptions& options);

/// A markdown table of CompareWithPaper(): the paper's values beside ours with the differences
/// (mm and degrees); a difference beyond its tolerance is bold, and the last column says "yes"
/// or "**NO**" (also for an orientation missing on either side).
std::string PaperComparisonMarkdown(const TableAnalysis& table,
                                    const PaperComparisonOptions& options);

/// Table I as markdown: for the paper's pan (`comparison` given) PaperComparisonMarkdown();
/// for an object the paper has no table of (`comparison` null), our table alone: per
/// orientation the trials averaged and the mean pre-grasp (PG) and grasp (G) wrist positions
/// relative to the object centre (d in m, eta in deg from world +x).
std::string TableIMarkdown(const TableAnalysis& table, const PaperComparisonOptions* comparison);

/// The `graspsynth-analysis/1` report of `analysis` (format in this file's description), as
/// indented JSON text. `comparison` is null for an object that is not the paper's
/// (ObjectModel::paper_object): then `paper_comparison` is null.
std::string AnalysisReportJson(const DemonstrationAnalysis& analysis,
                               const PaperComparisonOptions* comparison);

}  // namespace graspsynth
