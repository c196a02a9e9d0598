#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the simulation's results that the study's rows
/// carry: a trial's hold quality, a replay's physics, the sensitivity table; and the ranges of
/// its enums (trial outcomes, physics factors). They drive the job bytes and the Python classes;
/// the reports write these types in their own JSON form (studies/trial_json.hpp: degrees, rounded
/// figures, the load bearers).

#include "common/field_list.hpp"
#include "simulation/physics_perturbation.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial_judge.hpp"

namespace graspsynth {

template <>
struct EnumRange<TrialOutcome> {
  static constexpr TrialOutcome kLast = TrialOutcome::kUnstable;
};

template <>
struct EnumRange<PhysicsFactor> {
  static constexpr PhysicsFactor kLast = PhysicsFactor::kStep;
};

/// HoldQuality's fields (rad, m; load_share: the fingers in kFingerNames order, then the palm).
template <class V, class Row>
requires SameStruct<Row, HoldQuality>
void VisitFields(V& v, Row& r) {
  v(Field("end_tilt").Brief(), r.end_tilt);
  v(Field("max_tilt").Brief(), r.max_tilt);
  v(Field("slip").Brief(), r.slip);
  v(Field("slip_angle"), r.slip_angle);
  v(Field("contacts").Brief(), r.contacts);
  v(Field("load_share"), r.load_share);
}

/// PhysicsVariation's fields (factors; object_com_offset in the object frame, m).
template <class V, class Row>
requires SameStruct<Row, PhysicsVariation>
void VisitFields(V& v, Row& r) {
  v(Field("object_hand_friction").Brief(), r.object_hand_friction);
  v(Field("object_table_friction").Brief(), r.object_table_friction);
  v(Field("contact_stiffness").Brief(), r.contact_stiffness);
  v(Field("contact_damping").Brief(), r.contact_damping);
  v(Field("object_mass").Brief(), r.object_mass);
  v(Field("object_com_offset"), r.object_com_offset);
  v(Field("hand_effort").Brief(), r.hand_effort);
}

/// PhysicsDraw's fields (time_step, s; 0: the trial's own).
template <class V, class Row>
requires SameStruct<Row, PhysicsDraw>
void VisitFields(V& v, Row& r) {
  v(Field("variation"), r.variation);
  v(Field("time_step").Brief(), r.time_step);
}

/// SensitivityCell's fields.
template <class V, class Row>
requires SameStruct<Row, SensitivityCell>
void VisitFields(V& v, Row& r) {
  v(Field("physics"), r.physics);
  v(Field("trials").Brief(), r.trials);
  v(Field("successes").Brief(), r.successes);
  v(Field("failures").Brief(), r.failures);
}

/// SensitivityRow's fields.
template <class V, class Row>
requires SameStruct<Row, SensitivityRow>
void VisitFields(V& v, Row& r) {
  v(Field("factor").Brief(), r.factor);
  v(Field("low"), r.low);
  v(Field("high"), r.high);
}

/// SensitivityResult's fields (wall_time, s).
template <class V, class Row>
requires SameStruct<Row, SensitivityResult>
void VisitFields(V& v, Row& r) {
  v(Field("trials_per_cell").Brief(), r.trials_per_cell);
  v(Field("rows"), r.rows);
  v(Field("wall_time"), r.wall_time);
}

}  // namespace graspsynth
