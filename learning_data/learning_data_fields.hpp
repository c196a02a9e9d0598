#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the learning data's results: a demonstration log
/// (its metadata and samples) and a synthetic operator's trial, whose job bytes
/// (operator-trial/1, common/field_codec.hpp) they drive; a demonstration's robustness score,
/// which they make into library.json's `scores`, Python's DemoScore and the selection's job
/// bytes; and the range of a sample's event. The log's own text form is its CSV
/// (learning_data/demo_log.hpp), written and read there.

#include "common/field_list.hpp"
#include "learning_data/demo_log.hpp"
#include "learning_data/grasp_library.hpp"
#include "learning_data/synthetic_operator.hpp"
#include "simulation/simulation_fields.hpp"

namespace graspsynth {

template <>
struct EnumRange<DemoEvent> {
  static constexpr DemoEvent kLast = DemoEvent::kEnd;
};

/// DemoMetadata's fields (theta_deg, deg; object_position, world, m).
template <class V, class Row>
requires SameStruct<Row, DemoMetadata>
void VisitFields(V& v, Row& r) {
  v(Field("format"), r.format);
  v(Field("theta_deg"), r.theta_deg);
  v(Field("object_position"), r.object_position);
  v(Field("trial"), r.trial);
  v(Field("operator_name"), r.operator_name);
  v(Field("sample_rate_hz"), r.sample_rate_hz);
  v(Field("extra"), r.extra);
}

/// DemoSample's fields (s, world m, the wrist quaternion w x y z, finger joints rad).
template <class V, class Row>
requires SameStruct<Row, DemoSample>
void VisitFields(V& v, Row& r) {
  v(Field("t"), r.t);
  v(Field("p_WH"), r.p_WH);
  v(Field("q_WH"), r.q_WH);
  v(Field("f"), r.f);
  v(Field("event"), r.event);
  v(Field("p_WO"), r.p_WO);
}

/// DemoLog's fields.
template <class V, class Row>
requires SameStruct<Row, DemoLog>
void VisitFields(V& v, Row& r) {
  v(Field("source"), r.source);
  v(Field("metadata"), r.metadata);
  v(Field("samples"), r.samples);
}

/// OperatorTrial's fields, in the order of the layout operator-trial/1.
template <class V, class Row>
requires SameStruct<Row, OperatorTrial>
void VisitFields(V& v, Row& r) {
  v(Field("position"), r.position);
  v(Field("theta_deg"), r.theta_deg);
  v(Field("index"), r.index);
  v(Field("strategy"), r.strategy);
  v(Field("sloppy"), r.sloppy);
  v(Field("success"), r.success);
  v(Field("outcome"), r.outcome);
  v(Field("reason"), r.reason);
  v(Field("attempts"), r.attempts);
  v(Field("log"), r.log);
}

/// DemoScore's fields, with their keys in library.json's `scores` (a version-2 library adds
/// the placement, x, y and theta_deg, GraspLibrary::HasPositions).
template <class V, class Row>
requires SameStruct<Row, DemoScore>
void VisitFields(V& v, Row& r) {
  v(Field("file").Json("/file").Brief(), r.file);
  v(Field("trial").Json("/trial"), r.trial);
  v(Field("theta_deg").Json("/theta_deg").Brief(), r.theta_deg);
  v(Field("xy"), r.xy);
  v(Field("trials").Json("/trials"), r.trials);
  v(Field("successes").Json("/successes"), r.successes);
  v(Field("score").Json("/score").Brief(), r.score);
  v(Field("ci_low").Json("/ci_low"), r.ci_low);
  v(Field("ci_high").Json("/ci_high"), r.ci_high);
  v(Field("nominal_success").Json("/nominal_success"), r.nominal_success);
  v(Field("seed").Json("/seed"), r.seed);
  v(Field("failures").Json("/failures"), r.failures);
  v(Field("selected").Json("/selected").Brief(), r.selected);
  v(Field("stopped").Json("/stopped").OmitEmpty(), r.stopped);
}

}  // namespace graspsynth
