#include "analysis/analysis_report.hpp"

#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>

#include "common/demand.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

json Xy(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }

json PolarJson(const PolarMean& m) {
  return json{{"d", m.d},
              {"eta_deg", m.eta_deg},
              {"x", m.mean_xy.x()},
              {"y", m.mean_xy.y()},
              {"std_d", m.std_d},
              {"std_eta_deg", m.std_eta_deg},
              {"std_x", m.std_xy.x()},
              {"std_y", m.std_xy.y()}};
}

json LineJson(const Line2d& line, const FitResiduals& residuals) {
  return json{{"point", Xy(line.point)},          {"direction", Xy(line.direction)},
              {"angle_deg", line.angle() / kDeg}, {"offset_m", line.offset()},
              {"rms_m", residuals.rms},           {"max_m", residuals.max}};
}

json RowJson(const PaperTableRow& row) {
  return json{{"n", row.n},
              {"pregrasp", {{"d", row.pregrasp_d}, {"eta_deg", row.pregrasp_eta_deg}}},
              {"grasp", {{"d", row.grasp_d}, {"eta_deg", row.grasp_eta_deg}}}};
}

PaperTableRow FromStats(const OrientationStats& s) {
  return {s.theta_deg, s.n, s.pregrasp.d, s.pregrasp.eta_deg, s.grasp.d, s.grasp.eta_deg};
}

}  // namespace

const char* ToString(LinePoints points) {
  return points == LinePoints::kTrials ? "trials" : "orientation_means";
}

bool AnalysisOptions::IsValid(std::string* why) const {
  return segmentation.IsValid(why) && line.IsValid(why);
}

bool PaperComparisonOptions::IsValid(std::string* why) const {
  if (std::isfinite(distance_tolerance) && distance_tolerance >= 0.0 &&
      std::isfinite(angle_tolerance_deg) && angle_tolerance_deg >= 0.0) {
    return true;
  }
  if (why) *why = "the comparison tolerances must be finite and >= 0";
  return false;
}

namespace {

// The line principle over placements when the successful trials' objects stand at two or more
// positions; nullopt otherwise.
std::optional<PlacementLineFit> FitOverPlacements(const std::vector<SegmentedTrial>& trials,
                                                  const AnalysisOptions& options) {
  std::vector<PlacementLineSample> samples;
  for (const SegmentedTrial& trial : trials) {
    if (!trial.ok() || !trial.success) continue;
    const GraspingMotion& m = trial.motion;
    PlacementLineSample s;
    s.placement = Eigen::Vector3d(m.p_WO.x(), m.p_WO.y(), m.theta);
    s.wrist = m.grasp().p_WH - m.p_WO;
    samples.push_back(s);
  }
  if (options.line_points == LinePoints::kOrientationMeans) samples = MeanPerPlacement(samples);
  PlacementLineFit fit = FitPlacementLine(samples, options.line);
  if (fit.positions < 2) return std::nullopt;
  return fit;
}

}  // namespace

DemonstrationAnalysis AnalyzeDemonstrations(const DemoDirectory& demos,
                                            const AnalysisOptions& options) {
  RequireValid(options, "invalid analysis options");
  DemonstrationAnalysis analysis;
  analysis.directory = demos.directory;
  analysis.options = options;
  analysis.files = static_cast<int>(demos.logs.size());
  analysis.rejected = demos.rejected;

  std::vector<SegmentedTrial> trials;
  trials.reserve(demos.logs.size());
  for (const DemoLog& log : demos.logs) trials.push_back(Segment(log, options.segmentation));
  analysis.table = AnalyzeTable(trials);

  std::vector<double> mean_theta;
  std::vector<Eigen::Vector2d> mean_grasp, mean_pregrasp;
  for (const OrientationStats& row : analysis.table.orientations) {
    mean_theta.push_back(row.theta_deg * kDeg);
    mean_grasp.push_back(row.grasp.mean_xy);
    mean_pregrasp.push_back(row.pregrasp.mean_xy);
    if (options.line_points == LinePoints::kTrials) {
      for (const Eigen::Vector2d& p : row.grasp_points) {
        analysis.fit_theta.push_back(row.theta_deg * kDeg);
        analysis.fit_points.push_back(p);
      }
    }
  }
  if (options.line_points == LinePoints::kOrientationMeans) {
    analysis.fit_theta = mean_theta;
    analysis.fit_points = mean_grasp;
  }
  analysis.line = FitWristLine(analysis.fit_points, options.line);
  analysis.radial = FitRadialModel(analysis.fit_theta, analysis.fit_points);
  analysis.grasp_ranges = ComputeAngularRanges(mean_theta, mean_grasp);
  analysis.pregrasp_ranges = ComputeAngularRanges(mean_theta, mean_pregrasp);
  analysis.placement_line = FitOverPlacements(trials, options);
  return analysis;
}

const std::vector<PaperTableRow>& PaperTableI() {
  // our reading of the paper's garbled Table I: pre-grasp distance 0.41 m throughout, grasp
  // distance 0.378 -> 0.321 m, grasp angle -75.3 -> -40.6 deg.
  static const std::vector<PaperTableRow> rows = {
      {20, 5, 0.41, -71.5, 0.378, -75.3},  {30, 7, 0.41, -69.7, 0.371, -73.0},
      {40, 8, 0.41, -66.1, 0.358, -71.1},  {50, 10, 0.41, -62.6, 0.350, -69.0},
      {60, 10, 0.41, -52.4, 0.345, -63.1}, {70, 10, 0.41, -53.0, 0.337, -59.2},
      {80, 6, 0.41, -50.1, 0.329, -57.3},  {90, 6, 0.41, -44.1, 0.326, -47.1},
      {100, 5, 0.41, -39.8, 0.321, -40.6}};
  return rows;
}

std::vector<PaperComparisonRow> CompareWithPaper(const TableAnalysis& table,
                                                 const PaperComparisonOptions& options) {
  RequireValid(options, "invalid analysis options");
  // keyed by theta rounded to 1e-9 deg so that 20 and 20.0000000001 meet.
  std::map<long long, PaperComparisonRow> rows;
  const auto key = [](double theta_deg) { return std::llround(theta_deg * 1e9); };
  for (const PaperTableRow& paper : PaperTableI()) {
    PaperComparisonRow& row = rows[key(paper.theta_deg)];
    row.theta_deg = paper.theta_deg;
    row.paper = paper;
  }
  for (const OrientationStats& stats : table.orientations) {
    PaperComparisonRow& row = rows[key(stats.theta_deg)];
    row.theta_deg = stats.theta_deg;
    row.ours = FromStats(stats);
  }
  std::vector<PaperComparisonRow> result;
  for (auto& [k, row] : rows) {
    if (row.paper && row.ours) {
      PaperTableRow& d = row.difference;
      d.theta_deg = row.theta_deg;
      d.n = row.ours->n - row.paper->n;
      d.pregrasp_d = row.ours->pregrasp_d - row.paper->pregrasp_d;
      d.grasp_d = row.ours->grasp_d - row.paper->grasp_d;
      d.pregrasp_eta_deg =
          std::remainder(row.ours->pregrasp_eta_deg - row.paper->pregrasp_eta_deg, 360.0);
      d.grasp_eta_deg = std::remainder(row.ours->grasp_eta_deg - row.paper->grasp_eta_deg, 360.0);
      row.within_tolerance = std::abs(d.pregrasp_d) <= options.distance_tolerance &&
                             std::abs(d.grasp_d) <= options.distance_tolerance &&
                             std::abs(d.pregrasp_eta_deg) <= options.angle_tolerance_deg &&
                             std::abs(d.grasp_eta_deg) <= options.angle_tolerance_deg;
    }
    result.push_back(row);
  }
  return result;
}

std::string PaperComparisonMarkdown(const TableAnalysis& table,
                                    const PaperComparisonOptions& options) {
  const std::vector<PaperComparisonRow> rows = CompareWithPaper(table, options);
  std::string md;
  md +=
      "Table I of the paper beside ours: average pre-grasp (PG) and grasp (G) wrist positions "
      "relative to the object centre, top view (d in m, eta in deg from world +x). "
      "Differences are ours - paper; bold ones exceed the tolerance (" +
      FixedNumber(options.distance_tolerance * 1000.0, 1) + " mm, " +
      FixedNumber(options.angle_tolerance_deg, 1) + " deg).\n\n";
  md +=
      "| theta (deg) | n paper | n ours | d_PG paper | d_PG ours | diff (mm) | eta_PG paper | "
      "eta_PG ours | diff (deg) | d_G paper | d_G ours | diff (mm) | eta_G paper | eta_G ours | "
      "diff (deg) | within tolerance |\n";
  md += "|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
  int outside = 0;
  for (const PaperComparisonRow& row : rows) {
    const auto value = [](const std::optional<PaperTableRow>& r, double PaperTableRow::*field,
                          int decimals) {
      return r ? FixedNumber((*r).*field, decimals) : std::string("-");
    };
    const auto diff = [&](double value, double tolerance, double scale, int decimals) {
      if (!(row.paper && row.ours)) return std::string("-");
      const std::string text = Format("%+.*f", decimals, value * scale);
      return std::abs(value) > tolerance ? "**" + text + "**" : text;
    };
    const double dt = options.distance_tolerance;
    const double at = options.angle_tolerance_deg;
    md += "| " + StreamNumber(row.theta_deg) + " | " +
          (row.paper ? std::to_string(row.paper->n) : "-") + " | " +
          (row.ours ? std::to_string(row.ours->n) : "-") + " | " +
          value(row.paper, &PaperTableRow::pregrasp_d, 3) + " | " +
          value(row.ours, &PaperTableRow::pregrasp_d, 3) + " | " +
          diff(row.difference.pregrasp_d, dt, 1000.0, 1) + " | " +
          value(row.paper, &PaperTableRow::pregrasp_eta_deg, 1) + " | " +
          value(row.ours, &PaperTableRow::pregrasp_eta_deg, 1) + " | " +
          diff(row.difference.pregrasp_eta_deg, at, 1.0, 1) + " | " +
          value(row.paper, &PaperTableRow::grasp_d, 3) + " | " +
          value(row.ours, &PaperTableRow::grasp_d, 3) + " | " +
          diff(row.difference.grasp_d, dt, 1000.0, 1) + " | " +
          value(row.paper, &PaperTableRow::grasp_eta_deg, 1) + " | " +
          value(row.ours, &PaperTableRow::grasp_eta_deg, 1) + " | " +
          diff(row.difference.grasp_eta_deg, at, 1.0, 1) + " | ";
    if (row.within_tolerance) {
      md += "yes |\n";
    } else {
      ++outside;
      md += std::string("**NO**") + (!row.ours ? " (not in our data)" : "") +
            (!row.paper ? " (not in the paper)" : "") + " |\n";
    }
  }
  md += "\n" + std::to_string(rows.size() - outside) + " of " + std::to_string(rows.size()) +
        " orientations within tolerance.\n";
  return md;
}

std::string TableIMarkdown(const TableAnalysis& table, const PaperComparisonOptions* comparison) {
  if (comparison) return PaperComparisonMarkdown(table, *comparison);
  std::string md =
      "Table I of these demonstrations: average pre-grasp (PG) and grasp (G) wrist positions "
      "relative to the object centre, top view (d in m, eta in deg from world +x; the paper has "
      "no table for this object).\n\n"
      "| theta (deg) | n | d_PG | eta_PG | d_G | eta_G |\n"
      "|---:|---:|---:|---:|---:|---:|\n";
  for (const OrientationStats& row : table.orientations) {
    md += "| " + StreamNumber(row.theta_deg) + " | " + std::to_string(row.n) + " | " +
          FixedNumber(row.pregrasp.d, 3) + " | " + FixedNumber(row.pregrasp.eta_deg, 1) + " | " +
          FixedNumber(row.grasp.d, 3) + " | " + FixedNumber(row.grasp.eta_deg, 1) + " |\n";
  }
  return md;
}

namespace {

// The wrist-line fit: status, loss, and when usable the line, its residuals, the plain fit and
// the CGAL cross-check.
json WristLineJson(const DemonstrationAnalysis& analysis) {
  const WristLineResult& line = analysis.line;
  json wrist_line = {{"status", ToString(line.termination)},
                     {"message", line.message},
                     {"loss", ToString(line.loss)},
                     {"loss_scale_m", line.loss_scale},
                     {"n_points", analysis.fit_points.size()},
                     {"iterations", line.iterations}};
  if (line.usable()) {
    wrist_line.update(LineJson(line.line, line.residuals));
    wrist_line["residuals_m"] = line.residuals.per_point;
    wrist_line["plain"] = LineJson(line.plain_line, line.plain_residuals);
    json cgal = LineJson(line.cgal_line, line.cgal_residuals);
    cgal["angle_difference_deg"] = line.cgal_difference.angle / kDeg;
    cgal["offset_difference_m"] = line.cgal_difference.offset;
    cgal["agrees"] = line.cgal_agrees;
    wrist_line["cgal"] = cgal;
  }
  return wrist_line;
}

json Xyz(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json ResidualsJson(const PlacementLineResiduals& r) {
  json per_sample = json::array();
  for (const Eigen::Vector3d& e : r.per_sample) per_sample.push_back(Xyz(e));
  return {{"rms_xy_m", r.rms_xy},
          {"max_xy_m", r.max_xy},
          {"rms_z_m", r.rms_z},
          {"per_sample_m", per_sample}};
}

// The line principle over placements: the affine model, its residuals and those without the
// position terms.
json PlacementLineJson(const PlacementLineFit& fit) {
  json out = {{"valid", fit.valid},
              {"message", fit.message},
              {"model", "r = b + a_x (x - x_ref) + a_y (y - y_ref) + a_theta theta"},
              {"samples", fit.samples},
              {"positions", fit.positions}};
  if (!fit.valid) return out;
  out["reference_m"] = Xy(fit.reference);
  out["b_m"] = Xyz(fit.b);
  out["a_x"] = Xyz(fit.a_x);
  out["a_y"] = Xyz(fit.a_y);
  out["a_theta_m_per_rad"] = Xyz(fit.a_theta);
  out["line_angle_deg"] = std::isfinite(fit.line_angle_deg) ? json(fit.line_angle_deg) : json();
  out["iterations"] = fit.iterations;
  out["residuals"] = ResidualsJson(fit.residuals);
  out["theta_only"] = ResidualsJson(fit.theta_only);
  return out;
}

// Table I beside the paper's, row by row, with the tolerances.
json PaperComparisonJson(const TableAnalysis& table, const PaperComparisonOptions& comparison) {
  json rows = json::array();
  for (const PaperComparisonRow& row : CompareWithPaper(table, comparison)) {
    json r = {{"theta_deg", row.theta_deg},
              {"n_paper", row.paper ? json(row.paper->n) : json()},
              {"n_ours", row.ours ? json(row.ours->n) : json()},
              {"within_tolerance", row.within_tolerance}};
    if (row.paper) r["paper"] = RowJson(*row.paper);
    if (row.ours) r["ours"] = RowJson(*row.ours);
    if (row.paper && row.ours) {
      r["difference"] = RowJson(row.difference);
      r["note"] = "";
    } else {
      r["note"] = row.ours ? "not in the paper" : "not in our data";
    }
    rows.push_back(r);
  }
  return {{"distance_tolerance_m", comparison.distance_tolerance},
          {"angle_tolerance_deg", comparison.angle_tolerance_deg},
          {"rows", rows}};
}

}  // namespace

std::string AnalysisReportJson(const DemonstrationAnalysis& analysis,
                               const PaperComparisonOptions* comparison) {
  const AnalysisOptions& o = analysis.options;
  const TableAnalysis& table = analysis.table;
  json report;
  report["format"] = "graspsynth-analysis/1";
  report["directory"] = analysis.directory;
  report["options"] = {
      {"region",
       {{"shape",
         o.segmentation.region.shape == GraspRegionModel::Shape::kSphere ? "sphere" : "cylinder"},
        {"radius_m", o.segmentation.region.radius},
        {"height_m", o.segmentation.region.height}}},
      {"success_lift_m", o.segmentation.success_lift},
      {"line_points", ToString(o.line_points)},
      {"robust_loss", ToString(o.line.loss)},
      {"loss_scale_m", o.line.loss_scale}};
  report["counts"] = {{"files", analysis.files},
                      {"rejected", analysis.rejected.size()},
                      {"trials", table.trials},
                      {"used", table.used},
                      {"unsuccessful", table.unsuccessful.size()},
                      {"unsegmentable", table.unsegmentable.size()}};

  json orientations = json::array();
  for (const OrientationStats& row : table.orientations) {
    orientations.push_back({{"theta_deg", row.theta_deg},
                            {"n", row.n},
                            {"pregrasp", PolarJson(row.pregrasp)},
                            {"grasp", PolarJson(row.grasp)},
                            {"files", row.sources}});
  }
  report["orientations"] = orientations;

  report["wrist_line"] = WristLineJson(analysis);

  const RadialModelResult& radial = analysis.radial;
  report["radial_model"] = {{"valid", radial.valid},
                            {"model", "eta = theta + c, d constant"},
                            {"d_m", radial.d},
                            {"c_deg", radial.c / kDeg},
                            {"rms_m", radial.residuals.rms},
                            {"max_m", radial.residuals.max},
                            {"residuals_m", radial.residuals.per_point}};

  const double object_range = analysis.grasp_ranges.object_theta;
  report["angular_ranges"] = {
      {"object_theta_deg", object_range / kDeg},
      {"grasp_eta_deg", analysis.grasp_ranges.position_eta / kDeg},
      {"pregrasp_eta_deg", analysis.pregrasp_ranges.position_eta / kDeg},
      {"grasp_to_object_ratio",
       object_range > 0.0 ? json(analysis.grasp_ranges.position_eta / object_range) : json()}};

  if (analysis.placement_line)
    report["placement_line"] = PlacementLineJson(*analysis.placement_line);

  report["paper_comparison"] = comparison ? PaperComparisonJson(table, *comparison) : json();

  json rejected = json::array();
  for (const RejectedDemoFile& r : analysis.rejected) {
    rejected.push_back({{"file", r.file}, {"reason", r.reason}});
  }
  report["rejected"] = rejected;
  json skipped = json::array();
  for (const SkippedTrial& s : table.unsuccessful) {
    skipped.push_back({{"file", s.file}, {"reason", s.reason}, {"kind", "unsuccessful"}});
  }
  for (const SkippedTrial& s : table.unsegmentable) {
    skipped.push_back({{"file", s.file}, {"reason", s.reason}, {"kind", "unsegmentable"}});
  }
  report["skipped"] = skipped;
  return report.dump(2) + "\n";
}

}  // namespace graspsynth
