#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the study's results: a synthesis table's row
/// (StudyRow) and a method's totals (StudyMethodSummary). Each field is listed once, with its
/// place in synthesis.json (a JSON pointer) and synthesis.csv (a column) where those files carry
/// it; the list drives the job bytes (studies/study_codec.hpp, layout study-row/2), the JSON and
/// CSV writers (studies/study_report.hpp) and the Python classes (graspsynth.StudyRow).

#include "common/field_list.hpp"
#include "gate/gate_fields.hpp"
#include "simulation/simulation_fields.hpp"
#include "simulation_mujoco/mujoco_fields.hpp"
#include "solver/solver_fields.hpp"
#include "studies/study.hpp"

namespace graspsynth {

/// StudyRow's fields, in the order of its job bytes. The CSV columns are those of
/// kStudySynthesisCsvHeader, after x and y (the row's own position, when some row has one).
template <class V, class Row>
requires SameStruct<Row, StudyRow>
void VisitFields(V& v, Row& r) {
  v(Field("theta_deg").Json("/theta_deg").Csv(1).Brief(), r.theta_deg);
  v(Field("at").Json("/at").OmitEmpty().Csv(0, "x,y").Shortest(), r.at);
  v(Field("method").Json("/method").Csv(2).Brief(), r.method);
  v(Field("message").Json("/message"), r.message);
  v(Field("used").Json("/used").NullText("").Csv(4).Brief(), r.used);
  v(Field("fallback").Json("/fallback").Csv(5), r.fallback);
  v(Field("fallback_reason").Json("/fallback_reason"), r.fallback_reason);
  v(Field("refined").Json("/refined").Csv(6), r.refined);
  v(Field("gate_run").Json("/gate_run"), r.gate_run);
  v(Field("status").Json("/status").NullText("no_library").Csv(3).Brief(), r.status);
  v(Field("nominal_success").Json("/nominal/success").Csv(7).Brief(), r.nominal_success);
  v(Field("nominal_outcome").Json("/nominal/outcome").NullText("").Csv(8), r.nominal_outcome);
  v(Field("nominal_reason").Json("/nominal/reason"), r.nominal_reason);
  v(Field("trials").Json("/robustness/trials").Csv(9), r.trials);
  v(Field("successes").Json("/robustness/successes").Csv(10), r.successes);
  v(Field("robustness").Json("/robustness/score").Csv(11).Brief(), r.robustness);
  v(Field("ci_low").Json("/robustness/ci95/0").Csv(12), r.ci_low);
  v(Field("ci_high").Json("/robustness/ci95/1").Csv(13), r.ci_high);
  v(Field("passed").Json("/passed").Csv(14).Brief(), r.passed);
  v(Field("gate_reason").Json("/gate_reason"), r.gate_reason);
  v(Field("epsilon").Json("/quality/epsilon").Csv(15), r.epsilon);
  v(Field("force_closure").Json("/quality/force_closure").Csv(16), r.force_closure);
  v(Field("failures").Json("/robustness/failures").Csv(17), r.failures);
  v(Field("nominal_hold").Json("/hold").JsonNullIf(!r.gate_run), r.nominal_hold);
  v(Field("hold_margin").Json("/hold_margin").JsonNullIf(!r.gate_run), r.hold_margin);
  v(Field("hold_margin_shortfall").Json("/hold_margin_shortfall"), r.hold_margin_shortfall);
  v(Field("sensitivity").Json("/sensitivity"), r.sensitivity);
  v(Field("mujoco").Json("/mujoco").OmitEmpty(), r.mujoco);
  v(Field("seed").Json("/robustness/seed"), r.seed);
  // wall times and sources: in the bytes and in Python, not in the deterministic files.
  v(Field("synthesis_s"), r.synthesis_s);
  v(Field("gate_s"), r.gate_s);
  v(Field("source_thetas_deg"), r.source_thetas_deg);
}

/// StudyMethodSummary's fields; synthesis.json's `summary` carries all but mean_robustness_all.
template <class V, class Row>
requires SameStruct<Row, StudyMethodSummary>
void VisitFields(V& v, Row& r) {
  v(Field("method").Json("/method").Brief(), r.method);
  v(Field("rows").Json("/rows").Brief(), r.rows);
  v(Field("synthesized").Json("/synthesized"), r.synthesized);
  v(Field("nominal_successes").Json("/nominal_successes").Brief(), r.nominal_successes);
  v(Field("passed").Json("/passed").Brief(), r.passed);
  v(Field("fallbacks").Json("/fallbacks"), r.fallbacks);
  v(Field("mean_robustness").Json("/mean_robustness").Brief(), r.mean_robustness);
  v(Field("mean_robustness_all"), r.mean_robustness_all);
}

}  // namespace graspsynth
