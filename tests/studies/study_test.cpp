// Tests of the study's options and report builders (studies/study.hpp) on hand-made results;
// the study itself runs end to end in tests/apps/run_command_test.cpp.

#include "studies/study.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/grasp_library.hpp"
#include "scene/scene_model.hpp"
#include "studies/study_report.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

StudyOptions ValidOptions() {
  StudyOptions o;
  o.demos = "demos";
  return o;
}

std::string WhyInvalid(const StudyOptions& o) {
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  return why;
}

TEST(StudyOptions, DefaultsAreTheStudysOrientationsAndMethods) {
  const StudyOptions o = ValidOptions();
  std::string why;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  ASSERT_EQ(o.orientations.size(), 17u);
  EXPECT_EQ(o.orientations.front(), 20.0);
  EXPECT_EQ(o.orientations[1], 25.0);
  EXPECT_EQ(o.orientations.back(), 100.0);
  ASSERT_EQ(o.methods.size(), 2u);
  EXPECT_EQ(o.methods[0].Label(), "interp+refine");
  EXPECT_EQ(o.methods[1].Label(), "line+refine");
  EXPECT_EQ((StudyMethod{SynthesisMethod::kNearest, false}.Label()), "nearest");
}

TEST(StudyOptions, RejectsBadValuesNamingTheFieldAndValue) {
  StudyOptions o = ValidOptions();
  o.demos.clear();
  EXPECT_THAT(WhyInvalid(o), HasSubstr("demos"));
  o = ValidOptions();
  o.selection_perturbations = 0;
  EXPECT_THAT(WhyInvalid(o), HasSubstr("selection_perturbations: 0"));
  o = ValidOptions();
  o.gate_perturbations = -1;
  EXPECT_THAT(WhyInvalid(o), HasSubstr("gate_perturbations: -1"));
  o = ValidOptions();
  o.threads = -2;
  EXPECT_THAT(WhyInvalid(o), HasSubstr("threads: -2"));
  o = ValidOptions();
  o.min_robustness = 1.5;
  EXPECT_THAT(WhyInvalid(o), HasSubstr("min_robustness: 1.5"));
  o = ValidOptions();
  o.orientations = {40, NAN};
  EXPECT_THAT(WhyInvalid(o), HasSubstr("orientations[1]: nan"));
  o = ValidOptions();
  o.orientations = {40, 45, 40};
  EXPECT_THAT(WhyInvalid(o), HasSubstr("orientations[2]: 40 deg is given twice"));
  o = ValidOptions();
  o.orientations.clear();
  EXPECT_THAT(WhyInvalid(o), HasSubstr("orientations"));
  o = ValidOptions();
  o.methods = {{SynthesisMethod::kLine, true}, {SynthesisMethod::kLine, true}};
  EXPECT_THAT(WhyInvalid(o), HasSubstr("methods[1]: line+refine"));
  o = ValidOptions();
  o.analysis.segmentation.region.radius = -1.0;
  EXPECT_THAT(WhyInvalid(o), HasSubstr("analysis"));
}

TEST(StudyRowSeed, DependsOnSeedThetaAndMethodOnly) {
  EXPECT_EQ(StudyRowSeed(7, 45, "interp+refine"), StudyRowSeed(7, 45, "interp+refine"));
  EXPECT_NE(StudyRowSeed(7, 45, "interp+refine"), StudyRowSeed(8, 45, "interp+refine"));
  EXPECT_NE(StudyRowSeed(7, 45, "interp+refine"), StudyRowSeed(7, 45.5, "interp+refine"));
  EXPECT_NE(StudyRowSeed(7, 45, "interp+refine"), StudyRowSeed(7, 45, "line+refine"));
}

TEST(TableIReachability, EveryPaperGraspIsReachableInTheShippedScene) {
  const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  const std::vector<ReachabilityRow> rows = TableIReachability(robot, scene);
  ASSERT_EQ(rows.size(), 9u);
  for (const ReachabilityRow& r : rows) {
    EXPECT_TRUE(r.reachable) << r.theta_deg << ": " << r.reason;
    EXPECT_GT(r.psi_width_deg, 0.0);
    EXPECT_LT(r.fk_error, 1e-9);
  }
}

// Leave-one-out: each inner orientation of the shipped library (30, 40, ..., 90 deg) is
// synthesized without its own demonstration: no source of the grasp is the held-out
// orientation, and a blend (interp without fallback) comes from a neighbour on each side.
TEST(LeaveOneOutTable, TheHeldOutDemonstrationIsNeverASource) {
  const GraspLibrary library = ReadGraspLibrary(DefaultGraspLibraryPath());
  ASSERT_EQ(library.entries.size(), 9u);
  const SimulationModel model = LoadDefaultSimulationModel();
  SynthesisTableOptions options;
  options.methods = {{SynthesisMethod::kInterp, false}};
  options.gate.robustness.trials = 0;
  options.threads = 2;
  std::vector<std::string> stages;
  const std::vector<StudyRow> rows = LeaveOneOutTable(
      model, library, options, [&](const std::string& stage, int, int, const std::string&) {
        if (stages.empty() || stages.back() != stage) stages.push_back(stage);
      });
  ASSERT_EQ(rows.size(), 7u);
  EXPECT_EQ(stages.front(), "without 30");
  EXPECT_EQ(stages.back(), "without 90");
  for (size_t k = 0; k < rows.size(); ++k) {
    const StudyRow& r = rows[k];
    const double held_out = library.entries[k + 1].theta_deg;
    EXPECT_EQ(r.theta_deg, held_out);
    ASSERT_EQ(r.status, SynthesisStatus::kOk) << r.message;
    ASSERT_FALSE(r.source_thetas_deg.empty()) << held_out;
    for (double source : r.source_thetas_deg) EXPECT_NE(source, held_out) << held_out;
    if (!r.fallback) {  // the blend was used
      double below = -1e9, above = 1e9;
      for (double source : r.source_thetas_deg) {
        if (source < held_out) below = std::max(below, source);
        if (source > held_out) above = std::min(above, source);
      }
      EXPECT_EQ(below, library.entries[k].theta_deg) << held_out;
      EXPECT_EQ(above, library.entries[k + 2].theta_deg) << held_out;
    }
  }
  GraspLibrary two = library;
  two.entries.resize(2);
  EXPECT_THROW(LeaveOneOutTable(model, two, options), InputError);
}

// A hand-made result: two orientations, two methods; 45 deg line fails in the nominal trial,
// 60 deg interp is out of range, and a failure reason has a comma and a pipe.
StudyResult HandMadeResult() {
  StudyResult r;
  r.options = ValidOptions();
  r.options.orientations = {45, 60};
  r.options.gate_perturbations = 4;
  r.options.seed = 42;
  StudyRow ok;
  ok.theta_deg = 45;
  ok.method = "interp+refine";
  ok.status = SynthesisStatus::kOk;
  ok.used = SynthesisMethod::kNearest;
  ok.fallback = true;
  ok.fallback_reason.kind = FallbackKind::kTurnedDemo;
  ok.fallback_reason.bracket_reason = "the sides differ";
  ok.fallback_reason.lower_deg = 40;
  ok.fallback_reason.upper_deg = 50;
  ok.fallback_reason.used_deg = 40;
  ok.refined = true;
  ok.gate_run = true;
  ok.nominal_success = true;
  ok.nominal_outcome = TrialOutcome::kSuccess;
  ok.trials = 4;
  ok.successes = 4;
  ok.robustness = 1.0;
  ok.ci_low = 0.51;
  ok.ci_high = 1.0;
  ok.passed = true;
  ok.gate_reason = "passed: nominal success, robustness 4/4";
  ok.epsilon = 0.0123;
  ok.force_closure = true;
  ok.seed = 99;
  ok.synthesis_s = 0.002;
  ok.gate_s = 1.5;
  StudyRow dropped = ok;
  dropped.method = "line+refine";
  dropped.used = SynthesisMethod::kLine;
  dropped.fallback = false;
  dropped.fallback_reason = FallbackReason();
  dropped.nominal_success = false;
  dropped.nominal_outcome = TrialOutcome::kDropped;
  dropped.nominal_reason = "lifted 6 cm, then slipped | fell";
  dropped.successes = 1;
  dropped.robustness = 0.25;
  dropped.passed = false;
  dropped.failures = "dropped 2, not_lifted 1";
  dropped.gate_reason = "failed: nominal dropped";
  StudyRow out_of_range;
  out_of_range.theta_deg = 60;
  out_of_range.method = "interp+refine";
  out_of_range.status = SynthesisStatus::kOutOfRange;
  out_of_range.message = "60 deg is outside the library's range [20, 50]";
  StudyRow line60 = ok;
  line60.theta_deg = 60;
  line60.method = "line+refine";
  line60.used = SynthesisMethod::kLine;
  line60.fallback = false;
  r.rows = {ok, dropped, out_of_range, line60};
  r.total_s = 12.5;
  r.figure = "fig8.svg";
  return r;
}

TEST(StudySummary, CountsPerMethodInOrder) {
  const std::vector<StudyMethodSummary> s = SummarizeStudy(HandMadeResult().rows);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].method, "interp+refine");
  EXPECT_EQ(s[0].rows, 2);
  EXPECT_EQ(s[0].synthesized, 1);
  EXPECT_EQ(s[0].nominal_successes, 1);
  EXPECT_EQ(s[0].passed, 1);
  EXPECT_EQ(s[0].fallbacks, 1);
  EXPECT_DOUBLE_EQ(s[0].mean_robustness, 1.0);
  EXPECT_EQ(s[1].method, "line+refine");
  EXPECT_EQ(s[1].synthesized, 2);
  EXPECT_EQ(s[1].nominal_successes, 1);
  EXPECT_EQ(s[1].passed, 1);
  EXPECT_DOUBLE_EQ(s[1].mean_robustness, 0.625);
}

TEST(StudySynthesisCsv, HasTheHeaderAndOneQuotedSafeLinePerRow) {
  const std::string csv = StudySynthesisCsv(HandMadeResult().rows);
  std::istringstream in(csv);
  std::string line;
  std::vector<std::string> lines;
  while (std::getline(in, line)) lines.push_back(line);
  ASSERT_EQ(lines.size(), 5u);
  EXPECT_EQ(lines[0], kStudySynthesisCsvHeader);
  EXPECT_EQ(lines[1].rfind("45,interp+refine,ok,nearest,1,1,1,success,4,4,1,", 0), 0u) << lines[1];
  // a field with a comma is quoted, so the row keeps the header's column count.
  EXPECT_THAT(lines[2], HasSubstr(",\"dropped 2, not_lifted 1\""));
  EXPECT_EQ(lines[3].rfind("60,interp+refine,out_of_range,,0,", 0), 0u) << lines[3];
  EXPECT_THAT(csv, Not(HasSubstr("1.5")));  // no wall times in the deterministic table
}

TEST(StudySynthesisJson, HasTheFormatSummaryAndRowsWithoutWallTimes) {
  const nlohmann::json j = nlohmann::json::parse(StudySynthesisJson(HandMadeResult()));
  EXPECT_EQ(j["format"], "graspsynth-study-synthesis/1");
  EXPECT_EQ(j["seed"], 42);
  EXPECT_EQ(j["gate"]["perturbations"], 4);
  EXPECT_EQ(j["orientations_deg"], nlohmann::json({45.0, 60.0}));
  ASSERT_EQ(j["rows"].size(), 4u);
  EXPECT_EQ(j["rows"][1]["nominal"]["outcome"], "dropped");
  EXPECT_EQ(j["rows"][1]["robustness"]["successes"], 1);
  EXPECT_EQ(j["rows"][2]["status"], "out_of_range");
  EXPECT_FALSE(j["rows"][0].contains("synthesis_s"));
  EXPECT_EQ(j["summary"][1]["method"], "line+refine");
  EXPECT_EQ(j["summary"][1]["passed"], 1);
  const nlohmann::json t = nlohmann::json::parse(StudyTimingJson(HandMadeResult()));
  EXPECT_EQ(t["format"], "graspsynth-study-timing/1");
  EXPECT_DOUBLE_EQ(t["total_s"].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(t["rows"][0]["gate_s"].get<double>(), 1.5);
}

TEST(StudyReportMarkdown, StatesTheHeadlinesTablesAndFailureReasons) {
  const std::string md = StudyReportMarkdown(HandMadeResult());
  EXPECT_THAT(md, HasSubstr("# graspsynth study"));
  EXPECT_THAT(md, HasSubstr("interp+refine: 1/2 nominal successes, 1/2 passed the gate"));
  EXPECT_THAT(md, HasSubstr("line+refine: 1/2 nominal successes"));
  EXPECT_THAT(md, HasSubstr("![Fig. 8"));
  EXPECT_THAT(md, HasSubstr("(fig8.svg)"));
  // Table I beside the paper: every paper orientation is listed, ours missing here.
  EXPECT_THAT(md, HasSubstr("Table I: 0 of 9"));
  // the synthesis table: the fallback, the failed nominal trial, the out-of-range query.
  EXPECT_THAT(md, HasSubstr("| 45 | interp+refine | nearest (fallback) | success | 4/4 |"));
  EXPECT_THAT(md, HasSubstr("| 45 | line+refine | line | **dropped** | 1/4 |"));
  EXPECT_THAT(md, HasSubstr("| 60 | interp+refine | **out_of_range** |"));
  // the reasons of every shortfall, with the pipe escaped.
  EXPECT_THAT(md, HasSubstr("45 deg: nominal trial dropped: lifted 6 cm, then slipped \\| fell"));
  EXPECT_THAT(md, HasSubstr("60 deg: not synthesized (out_of_range): 60 deg is outside"));
  EXPECT_THAT(md, HasSubstr("45 deg, interp+refine used nearest: the bracket 40 - 50 deg cannot be "
                            "blended (the sides differ); used the nearer demonstration (40 deg) "
                            "turned with the object"));
}

// An object that is not the paper's pan: its own Table I, no comparison with the paper's.
TEST(StudyReportMarkdown, AnotherObjectHasItsOwnTableIAndNoPaperColumns) {
  StudyResult result = HandMadeResult();
  result.options.paper_object = false;
  OrientationStats row;
  row.theta_deg = 45.0;
  row.n = 3;
  row.grasp.d = 0.2;
  row.grasp.eta_deg = -110.0;
  row.pregrasp.d = 0.41;
  row.pregrasp.eta_deg = -60.0;
  result.analysis.table.orientations = {row};
  const std::string md = StudyReportMarkdown(result);
  EXPECT_THAT(md, HasSubstr("- Table I: 1 orientations (the paper has no table for this object)"));
  EXPECT_THAT(md, HasSubstr("| 45 | 3 | 0.410 | -60.0 | 0.200 | -110.0 |"));
  EXPECT_THAT(md, Not(HasSubstr("d_PG paper")));
  EXPECT_THAT(md, Not(HasSubstr("of the paper's orientations within")));
}

TEST(StudyReportMarkdown, SectionsComeInOrder) {
  StudyResult result = HandMadeResult();
  ReachabilityRow reach;
  reach.theta_deg = 45;
  reach.reachable = true;
  result.reachability = {reach};
  const std::string md = StudyReportMarkdown(result);
  size_t at = 0;
  for (const char* heading :
       {"# graspsynth study", "## Summary", "## Demonstrations and Table I", "## Fig. 8",
        "## Wrist line and radial strategy", "## Kinematics check of the paper's grasps",
        "## Grasp library", "## Synthesis and physics validation",
        "## Where a method falls short"}) {
    const size_t found = md.find(heading, at);
    ASSERT_NE(found, std::string::npos) << heading << " missing or out of order";
    at = found;
  }
}

TEST(StudyReportMarkdown, SaysHowManySelectionReplaysRanWhenSomeStopped) {
  StudyResult result = HandMadeResult();
  GraspLibrary& library = result.selection.library;
  library.perturbations = 20;
  DemoScore full;
  full.file = "a.csv";
  full.theta_deg = 45;
  full.trials = 20;
  full.successes = 20;
  full.selected = true;
  DemoScore stopped = full;
  stopped.file = "b.csv";
  stopped.trials = 0;
  stopped.successes = 0;
  stopped.selected = false;
  stopped.stopped = "no replays: a.csv succeeded in all 20 of its replays and wins every tie";
  library.scores = {full};
  EXPECT_THAT(StudyReportMarkdown(result), Not(HasSubstr("stopped replaying")));
  library.scores = {full, stopped};
  EXPECT_THAT(StudyReportMarkdown(result),
              HasSubstr("2 successful demonstrations scored with up to 20 perturbed replays each: "
                        "1 of them stopped replaying once they could no longer win their "
                        "orientation (library.json's `stopped`; their scores count the replays "
                        "that ran), so 20 of 40 perturbed replays ran."));
}

TEST(StudyRowNames, UnsetStatusIsNoLibraryAndUnsetOutcomeIsEmpty) {
  StudyRow row;
  row.theta_deg = 50;
  row.method = "interp+refine";
  row.message = "the selection made an empty library";
  EXPECT_EQ(StatusName(row), "no_library");
  EXPECT_EQ(NominalOutcomeName(row), "");
  EXPECT_THAT(StudySynthesisCsv({row}), HasSubstr("\n50,interp+refine,no_library,,0,0,0,,0,0,"));
  EXPECT_THAT(ShortfallMarkdown({row}),
              HasSubstr("50 deg: not synthesized (no_library): the selection made an empty"));
  row.status = SynthesisStatus::kUnreachable;
  row.nominal_outcome = TrialOutcome::kKnockedOver;
  EXPECT_EQ(StatusName(row), "unreachable");
  EXPECT_EQ(NominalOutcomeName(row), "knocked_over");
}

TEST(StudyReportMarkdown, SaysWhyFig8IsMissing) {
  StudyResult r = HandMadeResult();
  r.figure.clear();
  r.figure_note = "gnuplot could not be started";
  const std::string md = StudyReportMarkdown(r);
  EXPECT_THAT(md, Not(HasSubstr("![Fig. 8")));
  EXPECT_THAT(md, HasSubstr("Not drawn: gnuplot could not be started"));
}

TEST(StudyMethod, LabelsRoundTripThroughTheParser) {
  for (const std::string label :
       {"interp", "interp+refine", "line+refine", "nearest", "interp+ceres", "interp+nlopt",
        "interp+refine/arc", "interp/arc/joint", "line+nlopt/spline", "interp+refine/strict",
        "interp+refine/slide", "nearest+refine/strict/slide"}) {
    EXPECT_EQ(ParseStudyMethod(label).Label(), label);
  }
  const StudyMethod m = ParseStudyMethod("interp+ceres/arc/spline");
  EXPECT_TRUE(m.refine);
  EXPECT_TRUE(m.ceres);
  EXPECT_FALSE(m.nlopt);
  const SynthesisOptions o = m.Options();
  EXPECT_EQ(o.refinement_stages, RefinementStages{RefinementStage::kCeres});
  EXPECT_EQ(o.generation.blend.resample, ResampleMode::kArcLength);
  EXPECT_EQ(o.reach.method, ReachMethod::kSpline);
  EXPECT_FALSE(ParseStudyMethod("interp").Options().refines());
  EXPECT_FALSE(ParseStudyMethod("interp+refine").Options().grip_slide.has_value());
  EXPECT_TRUE(ParseStudyMethod("interp+refine/slide").Options().grip_slide.has_value());
  // the slide checks the refinement's constraints: without a refinement it is refused.
  EXPECT_THROW(ParseStudyMethod("interp/slide"), InputError);
}

TEST(StudyMethod, EachLabelBuildsThePipelineItNames) {
  using S = RefinementStage;
  struct Expected {
    std::string label;
    SynthesisMethod method;
    RefinementStages stages;
    ResampleMode resample;
    ReachMethod reach;
    bool source_thresholds;
  };
  const ResampleMode time = ResampleMode::kNormalizedTime, arc = ResampleMode::kArcLength;
  for (const Expected& e : std::vector<Expected>{
           {"interp", SynthesisMethod::kInterp, {}, time, ReachMethod::kAuto, true},
           {"interp+refine",
            SynthesisMethod::kInterp,
            {S::kCeres, S::kNlopt},
            time,
            ReachMethod::kAuto,
            true},
           {"line+ceres", SynthesisMethod::kLine, {S::kCeres}, time, ReachMethod::kAuto, true},
           {"nearest+nlopt",
            SynthesisMethod::kNearest,
            {S::kNlopt},
            time,
            ReachMethod::kAuto,
            true},
           {"interp+refine/arc",
            SynthesisMethod::kInterp,
            {S::kCeres, S::kNlopt},
            arc,
            ReachMethod::kAuto,
            true},
           {"interp/spline", SynthesisMethod::kInterp, {}, time, ReachMethod::kSpline, true},
           {"interp+ceres/joint",
            SynthesisMethod::kInterp,
            {S::kCeres},
            time,
            ReachMethod::kJoint,
            true},
           {"interp+refine/strict",
            SynthesisMethod::kInterp,
            {S::kCeres, S::kNlopt},
            time,
            ReachMethod::kAuto,
            false},
       }) {
    const SynthesisOptions o = ParseStudyMethod(e.label).Options();
    EXPECT_EQ(o.generation.method, e.method) << e.label;
    EXPECT_EQ(o.refinement_stages, e.stages) << e.label;
    EXPECT_EQ(o.refines(), !e.stages.empty()) << e.label;
    EXPECT_EQ(o.generation.blend.resample, e.resample) << e.label;
    EXPECT_EQ(o.reach.method, e.reach) << e.label;
    EXPECT_EQ(o.source_thresholds.has_value(), e.source_thresholds) << e.label;
    std::string why;
    EXPECT_TRUE(o.IsValid(&why)) << e.label << ": " << why;
  }
}

TEST(StudyMethod, UnknownOrMisplacedPartsAreNamed) {
  for (const auto& [label, part] : std::vector<std::pair<std::string, std::string>>{
           {"blend", "'blend'"},
           {"interp+polish", "'+polish'"},
           {"interp+refine+ceres", "'+ceres'"},
           {"interp/arc+refine", "'interp/arc+refine'"},
           {"interp/auto", "'/auto'"}}) {
    try {
      ParseStudyMethod(label);
      ADD_FAILURE() << label << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << label << ": " << e.what();
    }
  }
}

TEST(StudyReport, SummaryCountsEveryRowAndShortfallsGiveTheReason) {
  const std::vector<StudyRow> rows = HandMadeResult().rows;
  const std::string summary = SummaryMarkdown(rows);
  for (const StudyMethodSummary& s : SummarizeStudy(rows)) {
    EXPECT_NE(summary.find("| " + s.method + " | " + std::to_string(s.rows) + " | "),
              std::string::npos)
        << summary;
    EXPECT_LE(s.mean_robustness_all, s.mean_robustness);
  }
  const std::string shortfall = ShortfallMarkdown(rows);
  for (const StudyRow& r : rows) {
    if (!r.passed && r.status == SynthesisStatus::kOk && !r.nominal_success) {
      EXPECT_NE(shortfall.find(NominalOutcomeName(r)), std::string::npos) << shortfall;
    }
  }
}

}  // namespace
}  // namespace graspsynth
