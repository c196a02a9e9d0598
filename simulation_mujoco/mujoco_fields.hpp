#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the MuJoCo sweep's summary (MujocoSweepSummary),
/// which a study's row carries when the gate ran MuJoCo too (its job bytes and its JSON), and
/// of its runs (MujocoSweepRun, for the reports' JSON); m and rad, as the structs, the keys
/// naming the unit. MujocoSweepJson writes a whole sweep.

#include <utility>

#include "common/field_list.hpp"
#include "common/field_text.hpp"
#include "simulation_mujoco/mujoco_sweep.hpp"

namespace graspsynth {

/// MujocoSweepSummary's fields (slip in m, slip angles in rad).
template <class V, class Row>
requires SameStruct<Row, MujocoSweepSummary>
void VisitFields(V& v, Row& r) {
  v(Field("runs").Json("/runs").Brief(), r.runs);
  v(Field("successes").Json("/successes").Brief(), r.successes);
  v(Field("success_fraction").Json("/success_fraction").Brief(), r.success_fraction);
  v(Field("slip_median").Json("/slip_median_m"), r.slip_median);
  v(Field("slip_worst").Json("/slip_worst_m"), r.slip_worst);
  v(Field("slip_angle_median").Json("/slip_angle_median_rad"), r.slip_angle_median);
  v(Field("slip_angle_worst").Json("/slip_angle_worst_rad"), r.slip_angle_worst);
  v(Field("failing").Json("/failing"), r.failing);
}

/// MujocoSweepRun's fields but its wall time (slip in m, slip_angle in rad).
template <class V, class Row>
requires SameStruct<Row, MujocoSweepRun>
void VisitFields(V& v, Row& r) {
  v(Field("setting").Json("/setting").Brief(), r.setting);
  v(Field("servo").Json("/servo").Brief(), r.servo);
  v(Field("outcome").Json("/outcome").Brief(), r.outcome);
  v(Field("reason").Json("/reason"), r.reason);
  v(Field("lift").Json("/lift_m"), r.lift);
  v(Field("slip").Json("/slip_m"), r.slip);
  v(Field("slip_angle").Json("/slip_angle_rad"), r.slip_angle);
}

/// The JSON of `sweep` (nlohmann's Json type): {"summary": {...}, "runs": [{...}, ...]}, each
/// from its field list; no wall times, so that the same sweep writes the same bytes.
template <class Json>
Json MujocoSweepJson(const MujocoSweepResult& sweep) {
  Json runs = Json::array();
  for (const MujocoSweepRun& run : sweep.runs) runs.push_back(FieldsJson<Json>(run));
  Json out;
  out["summary"] = FieldsJson<Json>(sweep.summary);
  out["runs"] = std::move(runs);
  return out;
}

}  // namespace graspsynth
