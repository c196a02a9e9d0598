#include "studies/study_report.hpp"

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "analysis/analysis_report.hpp"
#include "common/field_text.hpp"
#include "studies/study_fields.hpp"
#include "studies/trial_json.hpp"

namespace graspsynth {

namespace study_text {

// A row's orientation, and its position when it has one of its own: "60" or "60 @ (-0.3, 0.8)".
std::string Where(const StudyRow& r) {
  if (!r.at) return StreamNumber(r.theta_deg);
  return Format("%g @ (%g, %g)", r.theta_deg, r.at->x(), r.at->y());
}

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

std::string CsvField(const std::string& text) { return CsvText(text); }

}  // namespace study_text

namespace {

using nlohmann::json;
using study_text::Cell;
using study_text::Where;

// The JSON forms the reports share for the row's nested results (studies/trial_json.hpp), and a
// fallback's reason in words.
struct RowJsonForms {
  json operator()(const FallbackReason& f) const { return f.Text(); }
  json operator()(const HoldQuality& h) const { return HoldQualityJson<json>(h); }
  json operator()(const HoldMargin& m) const {
    return HoldMarginJson<json>(m, [](double x) { return RoundForReport(x); });
  }
  json operator()(const SensitivityResult& s) const {
    return SensitivityJson<json>(s, TrialOptions{}.step());
  }
};

json RowsJson(const std::vector<StudyRow>& rows) {
  json out = json::array();
  for (const StudyRow& r : rows) out.push_back(FieldsJson<json>(r, RowJsonForms{}));
  return out;
}

json SummaryJson(const std::vector<StudyRow>& rows) {
  json summary = json::array();
  for (const StudyMethodSummary& s : SummarizeStudy(rows)) summary.push_back(FieldsJson<json>(s));
  return summary;
}

// Why a row fell short, in one sentence ("" when it passed).
std::string ShortfallReason(const StudyRow& r) {
  if (r.status != SynthesisStatus::kOk) {
    return "not synthesized (" + StatusName(r) + "): " + r.message;
  }
  if (!r.nominal_success) {
    return "nominal trial " + NominalOutcomeName(r) + ": " + r.nominal_reason;
  }
  // a required hold margin that the nominal hold missed: the gate ran no replays.
  if (!r.passed && r.gate_reason.rfind("hold margin: ", 0) == 0) return r.gate_reason;
  if (!r.passed) {
    return "robustness " + Format("%d/%d", r.successes, r.trials) +
           (r.failures.empty() ? std::string() : " (failures: " + r.failures + ")") + ": " +
           r.gate_reason;
  }
  return "";
}

}  // namespace

std::string StatusName(const StudyRow& row) {
  return row.status ? ToString(*row.status) : "no_library";
}

std::string UsedName(const StudyRow& row) {
  return row.used ? std::string(ToString(*row.used)) : std::string();
}

std::string NominalOutcomeName(const StudyRow& row) {
  return row.nominal_outcome ? std::string(ToString(*row.nominal_outcome)) : std::string();
}

std::string StudySynthesisCsv(const std::vector<StudyRow>& rows) { return FieldsCsv(rows); }

std::string StudySynthesisJson(const StudyResult& result) {
  const StudyOptions& o = result.options;
  json j;
  j["format"] = kStudySynthesisFormat;
  j["demos"] = o.DemosName();
  j["seed"] = o.seed;
  j["orientations_deg"] = o.orientations;
  json methods = json::array();
  for (const StudyMethod& m : o.methods) methods.push_back(m.Label());
  j["methods"] = methods;
  j["selection_perturbations"] = o.selection_perturbations;
  j["gate"] = {{"perturbations", o.gate_perturbations},
               {"min_robustness", o.min_robustness},
               {"sensitivity_trials", o.sensitivity_trials},
               {"physics_fallback", o.physics_fallback}};
  j["gate"]["hold_margin"] = HoldMarginOptionsJson<json>(o.hold_margin);
  const PhysicsPerturbationOptions& p = o.perturbation.physics;
  j["physics_perturbation"] = {{"enabled", p.enabled},
                               {"friction_spread", p.friction},
                               {"stiffness_range", {p.stiffness_min, p.stiffness_max}},
                               {"damping_range", {p.damping_min, p.damping_max}},
                               {"mass_spread", p.mass},
                               {"com_offset_m", p.com_offset},
                               {"servo_force_spread", p.servo_force},
                               {"fine_step_s", p.fine_step},
                               {"fine_step_probability", p.fine_step_probability}};
  j["summary"] = SummaryJson(result.rows);
  j["rows"] = RowsJson(result.rows);
  return j.dump(2) + "\n";
}

std::string StudyRowsJson(const std::vector<StudyRow>& rows) {
  json j;
  j["summary"] = SummaryJson(rows);
  j["rows"] = RowsJson(rows);
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
    md << "| " << Where(r) << " | " << r.method << " | ";
    if (r.status != SynthesisStatus::kOk) {
      md << "**" << StatusName(r) << "** | | | | **no** | | " << Format("%.1f", r.synthesis_s * 1e3)
         << " | |\n";
      continue;
    }
    md << UsedName(r) << (r.fallback ? " (fallback)" : "") << " | "
       << (r.nominal_success ? "success" : "**" + NominalOutcomeName(r) + "**") << " | "
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
        md << "- " << Where(r) << " deg, " << r.method << " used " << UsedName(r) << ": "
           << Cell(r.fallback_reason.Text()) << "\n";
      }
    }
    md << "\n";
  }

  return md.str();
}

std::string HoldMarginMarkdown(const std::vector<StudyRow>& rows,
                               const HoldMarginOptions& options) {
  std::ostringstream md;
  md << "Thresholds (" << (options.require ? "required by the gate" : "reported only") << "):\n\n";
  for (const HoldMarginThreshold& t : HoldMarginThresholds(options)) {
    md << "- " << t.name << " = " << Format("%g", t.value) << ": " << t.reason << "\n";
  }
  md << "\n| theta (deg) | method | passed | slip (mm) | slip (deg) | end tilt (deg) | contacts "
        "t/i/m/r/l/palm | load-bearing links | epsilon (weights) | friction use max | mean | "
        "squeeze (weights) | misses |\n"
     << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const StudyRow& r : rows) {
    if (!r.gate_run) continue;
    const HoldMargin& m = r.hold_margin;
    std::string contacts;
    for (int c : m.contacts) contacts += (contacts.empty() ? "" : "/") + std::to_string(c);
    md << "| " << Where(r) << " | " << r.method << " | " << (r.passed ? "yes" : "no") << " | "
       << Format("%.1f", m.slip_mm) << " | " << Format("%.1f", m.slip_deg) << " | "
       << Format("%.1f", m.end_tilt_deg) << " | " << contacts << " | " << m.load_bearing_links
       << (m.fingertips_only ? " (tips)" : "") << " | " << Format("%.3f", m.epsilon_weight) << " | "
       << Format("%.2f", m.friction_use_max) << " | " << Format("%.2f", m.friction_use_mean)
       << " | " << Format("%.2f", m.normal_force_weight) << " | "
       << Cell(r.hold_margin_shortfall.empty() ? "-" : r.hold_margin_shortfall) << " |\n";
  }
  return md.str();
}

std::string HoldAndSensitivityMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream md;
  md << "| theta (deg) | method | end tilt (deg) | max tilt (deg) | slip (mm) | load on |";
  for (PhysicsFactor f : AllPhysicsFactors()) md << " " << ToString(f) << " |";
  md << "\n|---|---|---|---|---|---|";
  for (size_t k = 0; k < AllPhysicsFactors().size(); ++k) md << "---|";
  md << "\n";
  for (const StudyRow& r : rows) {
    if (!r.gate_run) continue;
    const HoldQuality& h = r.nominal_hold;
    md << "| " << Where(r) << " | " << r.method << " | " << Format("%.1f", h.end_tilt / kDeg)
       << " | " << Format("%.1f", h.max_tilt / kDeg) << " | " << Format("%.1f", h.slip * 1e3)
       << " | " << h.LoadBearers() << " |";
    for (size_t c = 0; c < AllPhysicsFactors().size(); ++c) {
      if (!r.sensitivity) {
        md << " - |";
        continue;
      }
      const SensitivityCell& lo = r.sensitivity->rows[c].low;
      const SensitivityCell& hi = r.sensitivity->rows[c].high;
      md << " " << lo.successes << "/" << lo.trials << " · " << hi.successes << "/" << hi.trials
         << " |";
    }
    md << "\n";
  }
  return md.str();
}

std::string EnginesMarkdown(const std::vector<StudyRow>& rows) {
  std::ostringstream md;
  for (const StudyRow& r : rows) {
    if (!r.mujoco) continue;
    if (md.tellp() == 0) {
      md << "| theta (deg) | method | ODE nominal | ODE robustness | MuJoCo held | MuJoCo slip "
            "median (mm / deg) | worst (mm / deg) | MuJoCo failing |\n"
            "|---|---|---|---|---|---|---|---|\n";
    }
    const MujocoSweepSummary& m = *r.mujoco;
    md << "| " << Where(r) << " | " << r.method << " | "
       << (r.nominal_success ? "success" : "**" + NominalOutcomeName(r) + "**") << " | "
       << (r.trials > 0 ? Format("%d/%d", r.successes, r.trials) : std::string("-")) << " | "
       << Format("%d/%d", m.successes, m.runs) << " | "
       << Format("%.1f / %.1f", 1e3 * m.slip_median, m.slip_angle_median / kDeg) << " | "
       << Format("%.1f / %.1f", 1e3 * m.slip_worst, m.slip_angle_worst / kDeg) << " | "
       << (m.failing.empty() ? std::string("-") : Cell(m.failing)) << " |\n";
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
      md << "  - " << Where(r) << " deg: " << Cell(ShortfallReason(r)) << "\n";
    }
  }
  if (!any_shortfall) md << "\nNo shortfall.\n";
  return md.str();
}

namespace {

// Successful demonstrations per orientation of the library's scores, deg.
std::map<double, int> SuccessfulByOrientation(const GraspLibrary& library) {
  std::map<double, int> successful;
  for (const DemoScore& s : library.scores) ++successful[s.theta_deg];
  return successful;
}

// The title, the options and the wall times.
void OptionsSection(const StudyResult& result, std::ostringstream& md) {
  const StudyOptions& o = result.options;
  md << "# graspsynth study\n\n";
  md << "Demonstrations `" << o.DemosName() << "`, seed " << o.seed << ", "
     << o.selection_perturbations << " perturbed replays per demonstration in the selection, "
     << o.gate_perturbations << " perturbed replays per synthesized grasp (gate: nominal success "
     << "and robustness >= " << Format("%.2f", o.min_robustness) << "), the physics "
     << (o.perturbation.physics.enabled ? "perturbed" : "as modelled") << " in every replay, "
     << o.sensitivity_trials << " replays per end of each physics factor's range in the "
     << "sensitivity tables"
     << (o.physics_fallback ? "; an interp blend whose nominal trial fails gives way to the "
                              "fallbacks of a bracket that cannot be blended"
                            : "")
     << ". Orientations (deg):";
  for (size_t i = 0; i < o.orientations.size(); ++i) {
    md << (i ? ", " : " ") << StreamNumber(o.orientations[i]);
  }
  md << ". Methods:";
  for (size_t i = 0; i < o.methods.size(); ++i) md << (i ? ", " : " ") << o.methods[i].Label();
  md << ".\n\n";
  md << Format(
      "Wall time: analysis %.1f s, selection %.1f s, synthesis and validation %.1f s, total "
      "%.1f s.\n\n",
      result.analysis_s, result.selection_s, result.synthesis_s, result.total_s);
}

// The headline figures: Table I, the wrist line, the library, the kinematics, each method.
void SummarySection(const StudyResult& result, std::ostringstream& md) {
  const StudyOptions& o = result.options;
  const DemonstrationAnalysis& a = result.analysis;
  md << "## Summary\n\n";
  if (o.paper_object) {
    int within = 0, paper_rows = 0;
    for (const PaperComparisonRow& row : CompareWithPaper(a.table, o.comparison)) {
      if (row.paper) ++paper_rows;
      within += row.within_tolerance ? 1 : 0;
    }
    md << Format("- Table I: %d of %d of the paper's orientations within %.0f mm / %.0f deg.\n",
                 within, paper_rows, o.comparison.distance_tolerance * 1e3,
                 o.comparison.angle_tolerance_deg);
  } else {
    md << "- Table I: " << a.table.orientations.size()
       << " orientations (the paper has no table for this object).\n";
  }
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
  md << "- Library: " << result.selection.library.entries.size() << " of "
     << SuccessfulByOrientation(result.selection.library).size()
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
}

// The demonstrations read, Table I beside the paper, the files rejected; then Fig. 8.
void TableISection(const StudyResult& result, std::ostringstream& md) {
  const DemonstrationAnalysis& a = result.analysis;
  const TableAnalysis& t = a.table;
  md << "## Demonstrations and Table I\n\n";
  md << a.files << " logs read (" << a.rejected.size() << " rejected); " << t.used
     << " trials used, " << t.unsuccessful.size() << " unsuccessful, " << t.unsegmentable.size()
     << " unsegmentable.\n\n";
  md << TableIMarkdown(t, result.options.PaperComparison()) << "\n";
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
}

// The wrist line and the radial strategy, with the residual of each fitted point.
void WristLineSection(const DemonstrationAnalysis& a, std::ostringstream& md) {
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
}

// The reachability of the paper's grasp wrist poses (nothing when it was not checked).
void KinematicsSection(const std::vector<ReachabilityRow>& reachability, std::ostringstream& md) {
  if (reachability.empty()) return;
  md << "## Kinematics check of the paper's grasps\n\n";
  md << "The paper's Table I grasp wrist pose (palm down across the handle, elbow-up branch):\n\n"
        "| theta (deg) | d (m) | eta (deg) | reachable | feasible arm angle (deg) | FK error "
        "(m) |\n|---|---|---|---|---|---|\n";
  for (const ReachabilityRow& r : reachability) {
    md << "| " << StreamNumber(r.theta_deg) << " | " << Format("%.3f", r.d) << " | "
       << Format("%.1f", r.eta_deg) << " | " << (r.reachable ? "yes" : "**no**: " + r.reason)
       << " | " << Format("%.1f", r.psi_width_deg) << " | " << Format("%.1e", r.fk_error) << " |\n";
  }
  md << "\n";
}

// The representative selection: the demonstration chosen per orientation, then the issues.
void LibrarySection(const SelectionResult& selection, std::ostringstream& md) {
  md << "## Grasp library (representative selection)\n\n";
  const GraspLibrary& lib = selection.library;
  const auto [ran, all, stopped] = CountSelectionReplays(lib);
  md << selection.logs << " logs, " << selection.unsuccessful << " unsuccessful (not ranked), "
     << lib.scores.size() << " successful demonstrations scored with "
     << (stopped > 0 ? "up to " : "") << lib.perturbations << " perturbed replays each";
  if (stopped > 0) {
    md << ": " << stopped << " of them stopped replaying once they could no longer win their "
       << "orientation (library.json's `stopped`; their scores count the replays that ran), so "
       << ran << " of " << all << " perturbed replays ran";
  }
  md << ".\n\n";
  md << "| theta (deg) | successful | selected | score | 95% CI | nominal | failures |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const auto& [theta, n] : SuccessfulByOrientation(lib)) {
    const DemoScore* chosen = nullptr;
    for (const DemoScore& s : lib.scores) {
      if (s.selected && s.theta_deg == theta) chosen = &s;
    }
    if (!chosen) {
      md << "| " << StreamNumber(theta) << " | " << n
         << " | **none** (no replay succeeded) | | | | |\n";
      continue;
    }
    md << "| " << StreamNumber(theta) << " | " << n << " | `" << chosen->file << "` | "
       << Format("%d/%d", chosen->successes, chosen->trials) << " | "
       << Format("[%.2f, %.2f]", chosen->ci_low, chosen->ci_high) << " | "
       << (chosen->nominal_success ? "success" : "failed") << " | " << Cell(chosen->failures)
       << " |\n";
  }
  md << "\n";
  for (const SelectionIssue& issue : selection.issues) {
    md << "- " << ToString(issue.kind) << " `" << issue.file << "`: " << Cell(issue.reason) << "\n";
  }
  if (!selection.issues.empty()) md << "\n";
}

}  // namespace

std::string StudyReportMarkdown(const StudyResult& result) {
  std::ostringstream md;
  OptionsSection(result, md);
  SummarySection(result, md);  // the headline figures first
  TableISection(result, md);
  WristLineSection(result.analysis, md);
  KinematicsSection(result.reachability, md);
  LibrarySection(result.selection, md);
  md << "## Synthesis and physics validation\n\n"
     << "The rows run side by side, each on its share of the threads: a row's synthesis and "
        "gate times are its own wall times, and together they exceed the stage's.\n\n";
  md << SynthesisTableMarkdown(result.rows);
  md << "## Hold quality and sensitivity to the physics\n\n"
     << "The nominal trial's hold (tilt of the pan at the end of the hold and its largest, its "
        "slip in the hand since it left the table, the fingers carrying at least 10% of the "
        "contact force) and, per physics factor, the successes with that factor alone at the "
        "low · high end of its range (docs/architecture.md, \"Robustness under the contact "
        "model\").\n\n"
     << HoldAndSensitivityMarkdown(result.rows) << "\n";
  // with --engines ode,mujoco only: a default study's report is unchanged.
  if (const std::string engines = EnginesMarkdown(result.rows); !engines.empty()) {
    md << "## ODE and MuJoCo side by side\n\n"
       << "Each grasp that ODE passed, replayed in MuJoCo under its contact settings with both "
          "servo mappings (docs/mujoco.md); slip over the MuJoCo runs that held.\n\n"
       << engines << "\n";
  }
  md << "## Hold margin\n\n"
     << "How securely the nominal trial's hold sits in the hand at its end "
        "(gate/hold_margin.hpp): the pan's slip in the hand since it left the table, its tilt, "
        "the contact points per finger and the palm, the hand links carrying at least 10% of the "
        "contact force, the Ferrari-Canny epsilon of the contacts at their measured normal forces "
        "in the pan's weights, the largest and the force-weighted mean |f_t| / (mu f_n) of the "
        "load-bearing contacts, and the summed normal force in weights.\n\n"
     << HoldMarginMarkdown(result.rows, result.options.hold_margin) << "\n";
  md << "## Where a method falls short\n\n";
  md << ShortfallMarkdown(result.rows);
  return md.str();
}

}  // namespace graspsynth
