#include "solver/study.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "solver/analysis_report.hpp"
#include "solver/physics_gate.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

constexpr double kDeg = M_PI / 180.0;

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// printf into a std::string.
template <typename... Args>
std::string Format(const char* format, Args... args) {
  char buffer[512];
  std::snprintf(buffer, sizeof(buffer), format, args...);
  return buffer;
}

// A number with 17 significant digits (reads back bit for bit), "nan" for NaN.
std::string Num17(double value) { return Format("%.17g", value); }

// A theta for people: "45" or "47.5".
std::string Deg(double theta_deg) { return Format("%g", theta_deg); }

// A markdown table cell: pipes and line breaks would break the table.
std::string Cell(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '|') {
      out += "\\|";
    } else if (c == '\n') {
      out += ' ';
    } else {
      out += c;
    }
  }
  return out;
}

// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

// wrist height above the table for a grasp of the handle (reference/scene.md: 0.08-0.11 m).
constexpr double kWristHeight = 0.095;

// Wrist (hand-mount) pose for a grasp: palm down (x_H = -z_W), the hand's long axis z_H
// horizontal, across the handle and pointing from the wrist toward the handle's line.
Eigen::Isometry3d GraspWristPose(const SceneModel& scene, const PaperTableRow& row) {
  const double eta = row.grasp_eta_deg * kDeg;
  const Eigen::Vector2d p_OW = row.grasp_d * Eigen::Vector2d(std::cos(eta), std::sin(eta));
  const Eigen::Vector2d handle = scene.ObjectPose(row.theta_deg * kDeg).linear().col(0).head<2>();
  Eigen::Vector2d toward = p_OW.dot(handle) * handle - p_OW;  // foot of the perpendicular
  if (toward.norm() < 1e-6) toward = Eigen::Vector2d(-handle.y(), handle.x());
  toward.normalize();
  Eigen::Matrix3d R;
  R.col(0) = -Eigen::Vector3d::UnitZ();
  R.col(2) = Eigen::Vector3d(toward.x(), toward.y(), 0.0);
  R.col(1) = R.col(2).cross(R.col(0));
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = R;
  X_WH.translation() << scene.object.centre_xy + p_OW, scene.table.top_z + kWristHeight;
  return X_WH;
}

json RowJson(const StudyRow& r) {
  json j;
  j["theta_deg"] = r.theta_deg;
  j["method"] = r.method;
  j["status"] = r.status;
  j["message"] = r.message;
  j["used"] = r.used;
  j["fallback"] = r.fallback;
  j["fallback_reason"] = r.fallback_reason;
  j["refined"] = r.refined;
  j["gate_run"] = r.gate_run;
  j["nominal"] = {
      {"success", r.nominal_success}, {"outcome", r.nominal_outcome}, {"reason", r.nominal_reason}};
  j["robustness"] = {{"trials", r.trials},     {"successes", r.successes},
                     {"score", r.robustness},  {"ci95", {r.ci_low, r.ci_high}},
                     {"failures", r.failures}, {"seed", r.seed}};
  j["passed"] = r.passed;
  j["gate_reason"] = r.gate_reason;
  j["quality"] = {{"epsilon", r.epsilon}, {"force_closure", r.force_closure}};
  return j;
}

// Why a row fell short, in one sentence ("" when it passed).
std::string ShortfallReason(const StudyRow& r) {
  if (r.status != "ok") return "not synthesized (" + r.status + "): " + r.message;
  if (!r.nominal_success) return "nominal trial " + r.nominal_outcome + ": " + r.nominal_reason;
  if (!r.passed) {
    return "robustness " + Format("%d/%d", r.successes, r.trials) +
           (r.failures.empty() ? std::string() : " (failures: " + r.failures + ")") + ": " +
           r.gate_reason;
  }
  return "";
}

}  // namespace

const char* ToString(StudyStage stage) {
  switch (stage) {
    case StudyStage::kAnalysis:
      return "analysis";
    case StudyStage::kSelection:
      return "selection";
    case StudyStage::kSynthesis:
      return "synthesis";
  }
  return "?";
}

std::vector<double> StudyOptions::DefaultStudyOrientations() {
  std::vector<double> thetas;
  for (int t = 20; t <= 100; t += 5) thetas.push_back(t);
  return thetas;
}

bool StudyOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  if (demos.empty()) return fail("demos: no demonstration folder given");
  if (threads < 0) return fail("threads: " + std::to_string(threads) + " is negative");
  if (selection_perturbations < 1) {
    return fail("selection_perturbations: " + std::to_string(selection_perturbations) +
                " (needs >= 1)");
  }
  if (gate_perturbations < 0) {
    return fail("gate_perturbations: " + std::to_string(gate_perturbations) + " (needs >= 0)");
  }
  if (!(min_robustness >= 0.0 && min_robustness <= 1.0)) {
    return fail("min_robustness: " + Num17(min_robustness) + " (needs [0, 1])");
  }
  if (orientations.empty()) return fail("orientations: none given");
  for (size_t i = 0; i < orientations.size(); ++i) {
    if (!std::isfinite(orientations[i])) {
      return fail("orientations[" + std::to_string(i) + "]: " + Num17(orientations[i]) +
                  " is not a finite number of degrees");
    }
    for (size_t k = 0; k < i; ++k) {
      if (orientations[k] == orientations[i]) {
        return fail("orientations[" + std::to_string(i) + "]: " + Deg(orientations[i]) +
                    " deg is given twice");
      }
    }
  }
  if (methods.empty()) return fail("methods: none given");
  for (size_t i = 0; i < methods.size(); ++i) {
    for (size_t k = 0; k < i; ++k) {
      if (methods[k].Label() == methods[i].Label()) {
        return fail("methods[" + std::to_string(i) + "]: " + methods[i].Label() +
                    " is given twice");
      }
    }
  }
  std::string nested;
  if (!analysis.IsValid(&nested)) return fail("analysis: " + nested);
  if (!comparison.IsValid(&nested)) return fail("comparison: " + nested);
  return true;
}

uint64_t StudyRowSeed(uint64_t seed, double theta_deg, const std::string& method) {
  return DemoSeed(seed, "theta " + Num17(theta_deg) + " " + method);
}

std::vector<ReachabilityRow> TableIReachability(const RobotModel& robot, const SceneModel& scene) {
  const ArmModel& arm = robot.arm;
  std::vector<ReachabilityRow> rows;
  for (const PaperTableRow& g : PaperTableI()) {
    ReachabilityRow row;
    row.theta_deg = g.theta_deg;
    row.d = g.grasp_d;
    row.eta_deg = g.grasp_eta_deg;
    const Eigen::Isometry3d X_WF = GraspWristPose(scene, g) * robot.X_FH.inverse();
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, +1);
    const std::vector<Interval> feasible = FeasibleArmAngles(arm, form, +1, +1);
    for (const Interval& iv : feasible) row.psi_width_deg += iv.width() / kDeg;
    const std::optional<Interval> widest = WidestInterval(feasible);
    if (!widest) {
      row.reason = std::string(ToString(form.status));
      rows.push_back(row);
      continue;
    }
    const double psi = 0.5 * (widest->lo + widest->hi);
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, ArmBranch{});
    row.fk_error = DistanceBetween(ArmFlangePose(arm, s.q), X_WF).translation;
    row.reachable = s.status == IkStatus::kOk;
    if (!row.reachable) row.reason = "no IK solution at the middle of the widest arc";
    rows.push_back(row);
  }
  return rows;
}

namespace {

// The row of (theta, method) of a table with `seed`, before anything is known of it.
StudyRow NewRow(double theta, const StudyMethod& method, uint64_t seed) {
  StudyRow row;
  row.theta_deg = theta;
  row.method = method.Label();
  row.seed = StudyRowSeed(seed, theta, row.method);
  return row;
}

}  // namespace

std::vector<StudyRow> SynthesisTable(const SimulationModel& model, const GraspLibrary& library,
                                     const SynthesisTableOptions& options,
                                     const SynthesisTableProgress& progress) {
  const SynthesisModel synthesis(model.robot(), model.scene(), library);
  CollisionData data(synthesis.collision());
  const auto report = [&](int done, int total, const std::string& what) {
    if (progress) progress(done, total, what);
  };
  std::vector<StudyRow> rows;
  const int per_row = options.gate_perturbations + 1;
  const int total =
      static_cast<int>(options.orientations.size() * options.methods.size()) * per_row;
  int base = 0;
  for (double theta : options.orientations) {
    for (const StudyMethod& method : options.methods) {
      StudyRow row = NewRow(theta, method, options.seed);
      const std::string what = "theta " + Deg(theta) + " " + row.method;
      report(base, total, what);
      const auto t0 = std::chrono::steady_clock::now();
      const SynthesisResult s = SynthesizeGrasp(synthesis, theta, method.Options(), &data);
      row.synthesis_s = SecondsSince(t0);
      row.status = ToString(s.status);
      row.message = s.message;
      if (s.ok()) {
        row.used = ToString(s.used);
        row.fallback = s.fallback;
        row.fallback_reason = s.fallback_reason.Text();
        row.refined = s.refined;
        PhysicsGateOptions go;
        go.perturbations = options.gate_perturbations;
        go.min_robustness = options.min_robustness;
        go.perturbation = options.perturbation;
        go.seed = row.seed;
        go.threads = options.threads;
        const PhysicsGateResult gate = RunPhysicsGate(
            model, s.trajectory, go, [&](int done, int) { report(base + 1 + done, total, what); });
        row.gate_run = true;
        row.gate_s = gate.time_s;
        row.nominal_success = gate.nominal.success();
        row.nominal_outcome = std::string(ToString(gate.nominal.outcome));
        row.nominal_reason = gate.nominal.reason;
        if (gate.robustness_run) {
          row.trials = static_cast<int>(gate.robustness.trials.size());
          row.successes = gate.robustness.successes;
          row.robustness = gate.robustness.score;
          row.ci_low = gate.robustness.ci95.lo;
          row.ci_high = gate.robustness.ci95.hi;
          row.failures = FailureSummary(gate.robustness);
        }
        row.passed = gate.passed;
        row.gate_reason = gate.reason;
        row.epsilon = gate.quality.epsilon;
        row.force_closure = gate.quality.force_closure;
      }
      rows.push_back(row);
      base += per_row;
      report(base, total, what);
    }
  }
  return rows;
}

StudyResult RunStudy(const SimulationModel& model, const StudyOptions& options,
                     const StudyProgress& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("study: " + why);
  const auto study_start = std::chrono::steady_clock::now();
  StudyResult result;
  result.options = options;
  auto report = [&](StudyStage stage, int done, int total, const std::string& what) {
    if (progress) progress(stage, done, total, what);
  };

  // stage 1: segmentation and Table I (and the cheap kinematics check of the paper's grasps).
  auto start = std::chrono::steady_clock::now();
  report(StudyStage::kAnalysis, 0, 2, options.demos.string());
  const DemoDirectory demos = ReadDemoDirectory(options.demos);
  if (demos.logs.empty()) {
    throw InputError("study: no readable demonstration logs (*.csv) in '" + options.demos.string() +
                     "' (" + std::to_string(demos.rejected.size()) + " rejected)");
  }
  result.analysis = AnalyzeDemonstrations(demos, options.analysis);
  result.comparison = CompareWithPaper(result.analysis.table, options.comparison);
  result.reachability = TableIReachability(model.robot(), model.scene());
  report(StudyStage::kAnalysis, 2, 2, "Table I");
  result.analysis_s = SecondsSince(start);

  // stage 2: the representative selection makes the study's own library.
  start = std::chrono::steady_clock::now();
  SelectionOptions selection;
  selection.perturbations = options.selection_perturbations;
  selection.seed = options.seed;
  selection.threads = options.threads;
  selection.segmentation = options.analysis.segmentation;
  result.selection = SelectRepresentatives(model, demos.logs, options.demos.string(), selection,
                                           [&](int done, int total, const std::string& file) {
                                             report(StudyStage::kSelection, done, total, file);
                                           });
  for (const RejectedDemoFile& r : demos.rejected) {
    result.selection.issues.push_back({r.file, SelectionIssueKind::kUnreadable, r.reason});
  }
  result.selection_s = SecondsSince(start);

  // stage 3: synthesis and physics validation, one row per orientation and method.
  start = std::chrono::steady_clock::now();
  SynthesisTableOptions table;
  table.orientations = options.orientations;
  table.methods = options.methods;
  table.gate_perturbations = options.gate_perturbations;
  table.min_robustness = options.min_robustness;
  table.seed = options.seed;
  table.threads = options.threads;
  const auto table_progress = [&](int done, int total, const std::string& what) {
    report(StudyStage::kSynthesis, done, total, what);
  };
  const GraspLibrary& library = result.selection.library;
  std::string no_model;
  if (library.entries.empty()) {
    no_model = "the selection made an empty library (no orientation had a robust demonstration)";
  } else {
    try {
      result.rows = SynthesisTable(model, library, table, table_progress);
    } catch (const InputError& e) {
      no_model = e.what();
    }
  }
  if (!no_model.empty()) {
    for (double theta : options.orientations) {
      for (const StudyMethod& method : options.methods) {
        StudyRow row = NewRow(theta, method, options.seed);
        row.status = "no_library";
        row.message = no_model;
        result.rows.push_back(row);
      }
    }
  }
  result.synthesis_s = SecondsSince(start);
  result.total_s = SecondsSince(study_start);
  return result;
}

std::vector<StudyMethodSummary> SummarizeStudy(const std::vector<StudyRow>& rows) {
  std::vector<StudyMethodSummary> out;
  std::vector<double> robustness_sum;
  for (const StudyRow& r : rows) {
    size_t i = 0;
    while (i < out.size() && out[i].method != r.method) ++i;
    if (i == out.size()) {
      out.push_back({});
      out.back().method = r.method;
      robustness_sum.push_back(0.0);
    }
    StudyMethodSummary& s = out[i];
    ++s.rows;
    if (r.status == "ok") {
      ++s.synthesized;
      robustness_sum[i] += r.robustness;
    }
    s.nominal_successes += r.nominal_success ? 1 : 0;
    s.passed += r.passed ? 1 : 0;
    s.fallbacks += r.fallback ? 1 : 0;
  }
  for (size_t i = 0; i < out.size(); ++i) {
    out[i].mean_robustness = out[i].synthesized > 0 ? robustness_sum[i] / out[i].synthesized : 0;
    out[i].mean_robustness_all = robustness_sum[i] / out[i].rows;
  }
  return out;
}

std::string StudySynthesisCsv(const std::vector<StudyRow>& rows) {
  std::string csv = std::string(kStudySynthesisCsvHeader) + "\n";
  for (const StudyRow& r : rows) {
    const std::vector<std::string> fields = {Num17(r.theta_deg),
                                             r.method,
                                             r.status,
                                             r.used,
                                             r.fallback ? "1" : "0",
                                             r.refined ? "1" : "0",
                                             r.nominal_success ? "1" : "0",
                                             r.nominal_outcome,
                                             std::to_string(r.trials),
                                             std::to_string(r.successes),
                                             Num17(r.robustness),
                                             Num17(r.ci_low),
                                             Num17(r.ci_high),
                                             r.passed ? "1" : "0",
                                             Num17(r.epsilon),
                                             r.force_closure ? "1" : "0",
                                             r.failures};
    for (size_t i = 0; i < fields.size(); ++i) {
      if (i > 0) csv += ',';
      csv += CsvField(fields[i]);
    }
    csv += "\n";
  }
  return csv;
}

std::string StudySynthesisJson(const StudyResult& result) {
  const StudyOptions& o = result.options;
  json j;
  j["format"] = kStudySynthesisFormat;
  j["demos"] = o.demos.string();
  j["seed"] = o.seed;
  j["orientations_deg"] = o.orientations;
  json methods = json::array();
  for (const StudyMethod& m : o.methods) methods.push_back(m.Label());
  j["methods"] = methods;
  j["selection_perturbations"] = o.selection_perturbations;
  j["gate"] = {{"perturbations", o.gate_perturbations}, {"min_robustness", o.min_robustness}};
  json summary = json::array();
  for (const StudyMethodSummary& s : SummarizeStudy(result.rows)) {
    summary.push_back({{"method", s.method},
                       {"rows", s.rows},
                       {"synthesized", s.synthesized},
                       {"nominal_successes", s.nominal_successes},
                       {"passed", s.passed},
                       {"fallbacks", s.fallbacks},
                       {"mean_robustness", s.mean_robustness}});
  }
  j["summary"] = summary;
  json rows = json::array();
  for (const StudyRow& r : result.rows) rows.push_back(RowJson(r));
  j["rows"] = rows;
  return j.dump(2) + "\n";
}

std::string StudyTimingJson(const StudyResult& result) {
  json j;
  j["format"] = kStudyTimingFormat;
  j["threads"] = result.options.threads;
  j["stages_s"] = {{"analysis", result.analysis_s},
                   {"selection", result.selection_s},
                   {"synthesis", result.synthesis_s}};
  j["total_s"] = result.total_s;
  json rows = json::array();
  for (const StudyRow& r : result.rows) {
    rows.push_back({{"theta_deg", r.theta_deg},
                    {"method", r.method},
                    {"synthesis_s", r.synthesis_s},
                    {"gate_s", r.gate_s}});
  }
  j["rows"] = rows;
  return j.dump(2) + "\n";
}

std::string SynthesisTableMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream md;
  md << "| theta (deg) | method | used | nominal | robustness | 95% CI | gate | epsilon | "
        "synthesis (ms) | gate (s) |\n|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StudyRow& r : rows) {
    md << "| " << Deg(r.theta_deg) << " | " << r.method << " | ";
    if (r.status != "ok") {
      md << "**" << r.status << "** | | | | **no** | | " << Format("%.1f", r.synthesis_s * 1e3)
         << " | |\n";
      continue;
    }
    md << r.used << (r.fallback ? " (fallback)" : "") << " | "
       << (r.nominal_success ? "success" : "**" + r.nominal_outcome + "**") << " | "
       << (r.trials > 0 ? Format("%d/%d", r.successes, r.trials) : std::string("-")) << " | "
       << (r.trials > 0 ? Format("[%.2f, %.2f]", r.ci_low, r.ci_high) : std::string("-")) << " | "
       << (r.passed ? "yes" : "**no**") << " | "
       << (std::isfinite(r.epsilon) ? Format("%.4f", r.epsilon + 0.0) : std::string("-")) << " | "
       << Format("%.1f", r.synthesis_s * 1e3) << " | " << Format("%.1f", r.gate_s) << " |\n";
  }
  md << "\n";

  bool any_fallback = false;
  for (const StudyRow& r : rows) any_fallback |= r.fallback;
  if (any_fallback) {
    md << "Fallbacks:\n\n";
    for (const StudyRow& r : rows) {
      if (r.fallback) {
        md << "- " << Deg(r.theta_deg) << " deg, " << r.method << " used " << r.used << ": "
           << Cell(r.fallback_reason) << "\n";
      }
    }
    md << "\n";
  }

  return md.str();
}

std::string SummaryMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream md;
  md << "| method | orientations | synthesized | nominal successes | mean robustness (all rows) "
        "| passed the gate | fallbacks |\n|---|---|---|---|---|---|---|\n";
  for (const StudyMethodSummary& s : SummarizeStudy(rows)) {
    md << "| " << s.method << " | " << s.rows << " | " << s.synthesized << " | "
       << Format("%d (%.1f%%)", s.nominal_successes, 100.0 * s.nominal_successes / s.rows) << " | "
       << Format("%.2f", s.mean_robustness_all) << " | "
       << Format("%d (%.1f%%)", s.passed, 100.0 * s.passed / s.rows) << " | " << s.fallbacks
       << " |\n";
  }
  return md.str();
}

std::string ShortfallMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream md;
  bool any_shortfall = false;
  for (const StudyMethodSummary& s : SummarizeStudy(rows)) {
    if (s.passed == s.rows) {
      md << "- " << s.method << ": every orientation passed.\n";
      continue;
    }
    md << "- " << s.method << ": " << (s.rows - s.passed) << " of " << s.rows
       << " orientations did not pass:\n";
    for (const StudyRow& r : rows) {
      if (r.method != s.method || r.passed) continue;
      any_shortfall = true;
      md << "  - " << Deg(r.theta_deg) << " deg: " << Cell(ShortfallReason(r)) << "\n";
    }
  }
  if (!any_shortfall) md << "\nNo shortfall.\n";
  return md.str();
}

std::string StudyReportMarkdown(const StudyResult& result) {
  const StudyOptions& o = result.options;
  const DemonstrationAnalysis& a = result.analysis;
  const TableAnalysis& t = a.table;
  std::ostringstream md;
  md << "# graspsynth study\n\n";
  md << "Demonstrations `" << o.demos.string() << "`, seed " << o.seed << ", "
     << o.selection_perturbations << " perturbed replays per demonstration in the selection, "
     << o.gate_perturbations << " perturbed replays per synthesized grasp (gate: nominal success "
     << "and robustness >= " << Format("%.2f", o.min_robustness) << "). Orientations (deg):";
  for (size_t i = 0; i < o.orientations.size(); ++i) {
    md << (i ? ", " : " ") << Deg(o.orientations[i]);
  }
  md << ". Methods:";
  for (size_t i = 0; i < o.methods.size(); ++i) md << (i ? ", " : " ") << o.methods[i].Label();
  md << ".\n\n";
  md << Format(
      "Wall time: analysis %.1f s, selection %.1f s, synthesis and validation %.1f s, total "
      "%.1f s.\n\n",
      result.analysis_s, result.selection_s, result.synthesis_s, result.total_s);

  // the headline figures first.
  md << "## Summary\n\n";
  int within = 0, paper_rows = 0;
  for (const PaperComparisonRow& row : CompareWithPaper(t, o.comparison)) {
    if (row.paper) ++paper_rows;
    within += row.within_tolerance ? 1 : 0;
  }
  md << Format("- Table I: %d of %d of the paper's orientations within %.0f mm / %.0f deg.\n",
               within, paper_rows, o.comparison.distance_tolerance * 1e3,
               o.comparison.angle_tolerance_deg);
  if (a.line.usable()) {
    md << Format("- Wrist line: rms %.1f mm, max %.1f mm", a.line.residuals.rms * 1e3,
                 a.line.residuals.max * 1e3);
    if (a.radial.valid) {
      md << Format("; radial strategy: rms %.1f mm, max %.1f mm", a.radial.residuals.rms * 1e3,
                   a.radial.residuals.max * 1e3);
    }
    md << ".\n";
  } else {
    md << "- Wrist line: not fitted (" << a.line.message << ").\n";
  }
  std::map<double, int> successful;
  for (const DemoScore& s : result.selection.library.scores) ++successful[s.theta_deg];
  md << "- Library: " << result.selection.library.entries.size() << " of " << successful.size()
     << " orientations with successful demonstrations selected.\n";
  int reachable = 0;
  for (const ReachabilityRow& r : result.reachability) reachable += r.reachable ? 1 : 0;
  if (!result.reachability.empty()) {
    md << "- Kinematics: " << reachable << " of " << result.reachability.size()
       << " of the paper's grasp wrist poses reachable within the joint limits.\n";
  }
  for (const StudyMethodSummary& s : SummarizeStudy(result.rows)) {
    md << Format(
        "- %s: %d/%d nominal successes, %d/%d passed the gate, mean robustness %.2f over %d "
        "synthesized, %d fallback(s).\n",
        s.method.c_str(), s.nominal_successes, s.rows, s.passed, s.rows, s.mean_robustness,
        s.synthesized, s.fallbacks);
  }
  md << "\n";

  md << "## Demonstrations and Table I\n\n";
  md << a.files << " logs read (" << a.rejected.size() << " rejected); " << t.used
     << " trials used, " << t.unsuccessful.size() << " unsuccessful, " << t.unsegmentable.size()
     << " unsegmentable.\n\n";
  md << PaperComparisonMarkdown(t, o.comparison) << "\n";
  for (const RejectedDemoFile& r : a.rejected) {
    md << "- rejected `" << r.file << "`: " << Cell(r.reason) << "\n";
  }
  if (!a.rejected.empty()) md << "\n";

  md << "## Fig. 8\n\n";
  if (!result.figure.empty()) {
    md << "![Fig. 8: mean pre-grasp and grasp wrist positions per orientation, the wrist line]("
       << result.figure << ")\n\n";
  } else {
    md << "Not drawn" << (result.figure_note.empty() ? "" : ": " + result.figure_note) << ".\n\n";
  }

  md << "## Wrist line and radial strategy\n\n";
  if (a.line.usable()) {
    md << Format(
        "Wrist line (%s): point (%.4f, %.4f) m, direction angle %.2f deg, offset %.4f m; "
        "residual rms %.2f mm, max %.2f mm. CGAL cross-check %s.\n\n",
        a.line.message.c_str(), a.line.line.point.x(), a.line.line.point.y(),
        a.line.line.angle() / kDeg, a.line.line.offset(), a.line.residuals.rms * 1e3,
        a.line.residuals.max * 1e3, a.line.cgal_agrees ? "agrees" : "DISAGREES");
  } else {
    md << "Wrist line: " << a.line.message << "\n\n";
  }
  if (a.radial.valid) {
    md << Format(
        "Radial strategy (eta = theta + c, d constant): d = %.4f m, c = %.2f deg; residual rms "
        "%.2f mm, max %.2f mm.\n\n",
        a.radial.d, a.radial.c / kDeg, a.radial.residuals.rms * 1e3, a.radial.residuals.max * 1e3);
  }
  if (!a.fit_points.empty()) {
    md << "| theta (deg) | wrist-line residual (mm) | radial residual (mm) |\n|---|---|---|\n";
    for (size_t i = 0; i < a.fit_points.size(); ++i) {
      const auto& lr = a.line.residuals.per_point;
      const auto& rr = a.radial.residuals.per_point;
      md << "| " << Format("%.1f", a.fit_theta[i] / kDeg) << " | "
         << (i < lr.size() ? Format("%.2f", lr[i] * 1e3) : std::string("-")) << " | "
         << (i < rr.size() ? Format("%.2f", rr[i] * 1e3) : std::string("-")) << " |\n";
    }
    md << "\n";
  }

  if (!result.reachability.empty()) {
    md << "## Kinematics check of the paper's grasps\n\n";
    md << "The paper's Table I grasp wrist pose (palm down across the handle, elbow-up branch):\n\n"
          "| theta (deg) | d (m) | eta (deg) | reachable | feasible arm angle (deg) | FK error "
          "(m) |\n|---|---|---|---|---|---|\n";
    for (const ReachabilityRow& r : result.reachability) {
      md << "| " << Deg(r.theta_deg) << " | " << Format("%.3f", r.d) << " | "
         << Format("%.1f", r.eta_deg) << " | " << (r.reachable ? "yes" : "**no**: " + r.reason)
         << " | " << Format("%.1f", r.psi_width_deg) << " | " << Format("%.1e", r.fk_error)
         << " |\n";
    }
    md << "\n";
  }

  md << "## Grasp library (representative selection)\n\n";
  const GraspLibrary& lib = result.selection.library;
  md << result.selection.logs << " logs, " << result.selection.unsuccessful
     << " unsuccessful (not ranked), " << lib.scores.size() << " successful demonstrations scored "
     << "with " << lib.perturbations << " perturbed replays each.\n\n";
  md << "| theta (deg) | successful | selected | score | 95% CI | nominal | failures |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& [theta, n] : successful) {
    const DemoScore* chosen = nullptr;
    for (const DemoScore& s : lib.scores) {
      if (s.selected && s.theta_deg == theta) chosen = &s;
    }
    if (!chosen) {
      md << "| " << Deg(theta) << " | " << n << " | **none** (no replay succeeded) | | | | |\n";
      continue;
    }
    md << "| " << Deg(theta) << " | " << n << " | `" << chosen->file << "` | "
       << Format("%d/%d", chosen->successes, chosen->trials) << " | "
       << Format("[%.2f, %.2f]", chosen->ci_low, chosen->ci_high) << " | "
       << (chosen->nominal_success ? "success" : "failed") << " | " << Cell(chosen->failures)
       << " |\n";
  }
  md << "\n";
  for (const SelectionIssue& issue : result.selection.issues) {
    md << "- " << ToString(issue.kind) << " `" << issue.file << "`: " << Cell(issue.reason) << "\n";
  }
  if (!result.selection.issues.empty()) md << "\n";

  md << "## Synthesis and physics validation\n\n";
  md << SynthesisTableMarkdown(result.rows);
  md << "## Where a method falls short\n\n";
  md << ShortfallMarkdown(result.rows);
  return md.str();
}

}  // namespace graspsynth
