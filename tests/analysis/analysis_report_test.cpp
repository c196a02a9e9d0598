// Tests of the end-to-end analysis, the graspsynth-analysis/1 report and the paper comparison.

#include "analysis/analysis_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/analysis/table_i_demos.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

// The paper's tolerances: the reports of the paper's pan compare with its Table I.
const PaperComparisonOptions kPaper;

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

// The Table I set plus one dropped trial, one unsegmentable trial and one rejected file.
DemoDirectory TableIDirectory(double shifted_theta_deg = -1.0,
                              const Eigen::Vector2d& shift = {0.0, 0.0}) {
  DemoDirectory demos;
  demos.directory = "demos";
  demos.logs = testing::TableIDemos(shifted_theta_deg, shift);
  testing::TrialSpec spec;
  spec.theta_deg = 50.0;
  spec.lift = 0.01;
  spec.trial = "dropped";
  demos.logs.push_back(testing::MakeTrial(spec));
  spec.lift = 0.1;
  spec.pregrasp_xy = testing::Polar(0.7, -60.0);
  spec.grasp_xy = testing::Polar(0.6, -60.0);
  spec.trial = "outside";
  demos.logs.push_back(testing::MakeTrial(spec));
  demos.rejected.push_back({"demos/bad.csv", "demos/bad.csv:6: column 3 'wrist_y': ..."});
  return demos;
}

TEST(AnalysisReport, ReproducesTableIFromExactDemonstrations) {
  const DemonstrationAnalysis a = AnalyzeDemonstrations(TableIDirectory(), {});
  EXPECT_EQ(a.files, 69);  // the paper's 5+7+8+10+10+10+6+6+5 = 67 trials, plus 2
  ASSERT_EQ(a.table.orientations.size(), PaperTableI().size());
  for (size_t i = 0; i < PaperTableI().size(); ++i) {
    const PaperTableRow& paper = PaperTableI()[i];
    const OrientationStats& ours = a.table.orientations[i];
    SCOPED_TRACE(paper.theta_deg);
    EXPECT_EQ(ours.theta_deg, paper.theta_deg);
    EXPECT_EQ(ours.n, paper.n);
    EXPECT_NEAR(ours.pregrasp.d, paper.pregrasp_d, 1e-6);
    EXPECT_NEAR(ours.pregrasp.eta_deg, paper.pregrasp_eta_deg, 1e-9);
    EXPECT_NEAR(ours.grasp.d, paper.grasp_d, 1e-12);
    EXPECT_NEAR(ours.grasp.eta_deg, paper.grasp_eta_deg, 1e-9);
  }
  EXPECT_EQ(a.table.unsuccessful.size(), 1u);
  EXPECT_EQ(a.table.unsegmentable.size(), 1u);
  EXPECT_EQ(a.fit_points.size(), 9u);
  EXPECT_TRUE(a.line.usable());
  EXPECT_TRUE(a.line.cgal_agrees);
  EXPECT_TRUE(a.radial.valid);
  EXPECT_NEAR(a.grasp_ranges.position_eta * 180.0 / M_PI, 34.7, 1e-9);
  EXPECT_NEAR(a.grasp_ranges.object_theta * 180.0 / M_PI, 80.0, 1e-12);

  for (const PaperComparisonRow& row : CompareWithPaper(a.table, {})) {
    EXPECT_TRUE(row.within_tolerance) << row.theta_deg;
  }
  AnalysisOptions trials;
  trials.line_points = LinePoints::kTrials;
  const DemonstrationAnalysis b = AnalyzeDemonstrations(TableIDirectory(), trials);
  EXPECT_EQ(b.fit_points.size(), 67u);
  EXPECT_EQ(b.fit_theta.size(), 67u);
}

TEST(AnalysisReport, JsonHasTheDocumentedFields) {
  const DemonstrationAnalysis a = AnalyzeDemonstrations(TableIDirectory(), {});
  const json r = json::parse(AnalysisReportJson(a, &kPaper));
  EXPECT_EQ(r.at("format"), "graspsynth-analysis/1");
  EXPECT_EQ(r.at("directory"), "demos");
  EXPECT_EQ(r.at("options").at("region").at("shape"), "cylinder");
  EXPECT_EQ(r.at("options").at("region").at("radius_m"), 0.41);
  EXPECT_EQ(r.at("options").at("robust_loss"), "none");
  EXPECT_EQ(r.at("counts").at("files"), 69);
  EXPECT_EQ(r.at("counts").at("used"), 67);
  EXPECT_EQ(r.at("counts").at("rejected"), 1);

  const json& orientations = r.at("orientations");
  ASSERT_EQ(orientations.size(), 9u);
  const json& first = orientations[0];
  EXPECT_EQ(first.at("theta_deg"), 20.0);
  EXPECT_EQ(first.at("n"), 5);
  EXPECT_NEAR(first.at("pregrasp").at("d").get<double>(), 0.41, 1e-6);
  EXPECT_NEAR(first.at("pregrasp").at("eta_deg").get<double>(), -71.5, 1e-9);
  EXPECT_NEAR(first.at("grasp").at("d").get<double>(), 0.378, 1e-12);
  EXPECT_NEAR(first.at("grasp").at("eta_deg").get<double>(), -75.3, 1e-9);
  for (const char* key : {"x", "y", "std_d", "std_eta_deg", "std_x", "std_y"}) {
    EXPECT_TRUE(first.at("grasp").contains(key)) << key;
  }
  EXPECT_EQ(first.at("files").size(), 5u);

  const json& line = r.at("wrist_line");
  EXPECT_EQ(line.at("status"), "converged");
  ASSERT_EQ(line.at("point").size(), 2u);
  ASSERT_EQ(line.at("direction").size(), 2u);
  const Eigen::Vector2d direction(line["direction"][0].get<double>(),
                                  line["direction"][1].get<double>());
  EXPECT_NEAR(direction.norm(), 1.0, 1e-12);
  EXPECT_NEAR(line.at("rms_m").get<double>(), a.line.residuals.rms, 1e-15);
  EXPECT_NEAR(line.at("max_m").get<double>(), a.line.residuals.max, 1e-15);
  EXPECT_EQ(line.at("residuals_m").size(), 9u);
  EXPECT_EQ(line.at("cgal").at("agrees"), true);
  EXPECT_LT(line.at("cgal").at("angle_difference_deg").get<double>(), 1e-4);
  EXPECT_LT(line.at("cgal").at("offset_difference_m").get<double>(), 1e-6);
  EXPECT_TRUE(line.at("plain").contains("angle_deg"));

  const json& radial = r.at("radial_model");
  EXPECT_EQ(radial.at("valid"), true);
  EXPECT_GT(radial.at("rms_m").get<double>(), line.at("rms_m").get<double>());
  for (const char* key : {"d_m", "c_deg", "max_m", "residuals_m"}) {
    EXPECT_TRUE(radial.contains(key)) << key;
  }
  EXPECT_NEAR(r.at("angular_ranges").at("grasp_eta_deg").get<double>(), 34.7, 1e-9);
  EXPECT_NEAR(r.at("angular_ranges").at("object_theta_deg").get<double>(), 80.0, 1e-12);
  EXPECT_TRUE(r.at("angular_ranges").contains("pregrasp_eta_deg"));

  const json& comparison = r.at("paper_comparison");
  EXPECT_EQ(comparison.at("distance_tolerance_m"), 0.005);
  ASSERT_EQ(comparison.at("rows").size(), 9u);
  EXPECT_EQ(comparison["rows"][0].at("within_tolerance"), true);
  EXPECT_NEAR(comparison["rows"][0].at("difference").at("grasp").at("d").get<double>(), 0.0, 1e-12);

  ASSERT_EQ(r.at("rejected").size(), 1u);
  EXPECT_EQ(r["rejected"][0].at("file"), "demos/bad.csv");
  EXPECT_THAT(r["rejected"][0].at("reason").get<std::string>(), HasSubstr(":6:"));
  ASSERT_EQ(r.at("skipped").size(), 2u);
  EXPECT_EQ(r["skipped"][0].at("file"), "trial_dropped.csv");
  EXPECT_EQ(r["skipped"][0].at("kind"), "unsuccessful");
  EXPECT_EQ(r["skipped"][1].at("file"), "trial_outside.csv");
  EXPECT_EQ(r["skipped"][1].at("kind"), "unsegmentable");
  EXPECT_THAT(r["skipped"][1].at("reason").get<std::string>(), HasSubstr("never enters"));
}

TEST(AnalysisReport, JsonOfAnEmptyAnalysisIsStillComplete) {
  DemoDirectory demos;
  demos.directory = "empty";
  demos.rejected.push_back({"empty/x.csv", "empty/x.csv: empty file"});
  const json r = json::parse(AnalysisReportJson(AnalyzeDemonstrations(demos, {}), &kPaper));
  EXPECT_TRUE(r.at("orientations").empty());
  EXPECT_EQ(r.at("wrist_line").at("status"), "insufficient data");
  EXPECT_FALSE(r.at("wrist_line").contains("point"));
  EXPECT_EQ(r.at("radial_model").at("valid"), false);
  EXPECT_EQ(r.at("paper_comparison").at("rows").size(), 9u);
  EXPECT_EQ(r.at("rejected").size(), 1u);
}

TEST(AnalysisReport, MarkdownMarksRowsOutsideTheTolerance) {
  // the grasps of theta = 50 shifted by 1 cm: that row is outside 5 mm; the others are in.
  const DemonstrationAnalysis a =
      AnalyzeDemonstrations(TableIDirectory(50.0, Eigen::Vector2d(0.0, -0.01)), {});
  const std::vector<PaperComparisonRow> rows = CompareWithPaper(a.table, {});
  ASSERT_EQ(rows.size(), 9u);
  for (const PaperComparisonRow& row : rows) {
    EXPECT_EQ(row.within_tolerance, row.theta_deg != 50.0) << row.theta_deg;
  }
  const std::string md = PaperComparisonMarkdown(a.table, {});
  std::vector<std::string> lines;
  std::istringstream in(md);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| ", 0) == 0) lines.push_back(line);
  }
  ASSERT_EQ(lines.size(), 10u);  // header + 9 rows
  EXPECT_THAT(lines[0], HasSubstr("d_G paper"));
  for (size_t i = 1; i < lines.size(); ++i) {
    if (lines[i].rfind("| 50 |", 0) == 0) {
      EXPECT_THAT(lines[i], HasSubstr("**NO**"));
      EXPECT_THAT(lines[i], HasSubstr("| 0.350 |"));  // the paper's d_G
      EXPECT_THAT(lines[i], ::testing::ContainsRegex("\\*\\*[+-][0-9.]+\\*\\*"));  // bold diff
    } else {
      EXPECT_THAT(lines[i], HasSubstr("| yes |"));
      EXPECT_THAT(lines[i], Not(HasSubstr("**")));
    }
  }
  EXPECT_THAT(md, HasSubstr("8 of 9 orientations within tolerance"));
  EXPECT_THAT(md, HasSubstr("5.0 mm, 2.0 deg"));

  // a looser tolerance takes the row back in.
  PaperComparisonOptions loose;
  loose.distance_tolerance = 0.02;
  loose.angle_tolerance_deg = 5.0;
  EXPECT_THAT(PaperComparisonMarkdown(a.table, loose), HasSubstr("9 of 9 orientations"));
}

TEST(AnalysisReport, MarkdownMarksOrientationsMissingOnEitherSide) {
  DemoDirectory demos;
  testing::TrialSpec spec;
  spec.theta_deg = 110.0;  // not in the paper
  demos.logs.push_back(testing::MakeTrial(spec));
  const DemonstrationAnalysis a = AnalyzeDemonstrations(demos, {});
  const std::string md = PaperComparisonMarkdown(a.table, {});
  EXPECT_THAT(md, HasSubstr("| 20 | 5 | - |"));
  EXPECT_THAT(md, HasSubstr("(not in our data)"));
  EXPECT_THAT(md, HasSubstr("| 110 | - | 1 |"));
  EXPECT_THAT(md, HasSubstr("(not in the paper)"));
  EXPECT_THAT(md, HasSubstr("0 of 10 orientations within tolerance"));
}

TEST(AnalysisReport, PaperTableIIsOurReadingOfThePaper) {
  const std::vector<PaperTableRow>& rows = PaperTableI();
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(rows.front().theta_deg, 20.0);
  EXPECT_EQ(rows.back().theta_deg, 100.0);
  EXPECT_EQ(rows.front().grasp_d, 0.378);
  EXPECT_EQ(rows.back().grasp_d, 0.321);
  EXPECT_EQ(rows.front().grasp_eta_deg, -75.3);
  EXPECT_EQ(rows.back().grasp_eta_deg, -40.6);
  int n = 0;
  for (const PaperTableRow& row : rows) {
    EXPECT_EQ(row.pregrasp_d, 0.41);
    n += row.n;
  }
  EXPECT_EQ(n, 67);
}

}  // namespace
}  // namespace graspsynth
