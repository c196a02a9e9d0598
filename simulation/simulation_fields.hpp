#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the simulation's results: a trial's result and
/// hold quality, the perturbed replays (each replay and their score), a replay's physics, the
/// sensitivity table; and the ranges of its enums (trial outcomes, physics factors). They drive
/// the job bytes and the Python classes; the reports write these types in their own JSON form
/// (studies/trial_json.hpp: degrees, rounded figures, the load bearers).

#include "common/field_list.hpp"
#include "simulation/physics_perturbation.hpp"
#include "simulation/robustness.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"
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

/// HoldQuality's fields (rad, m; load_share: the groups of kLoadShareGroups, fingers then palm).
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

/// Interval's fields.
template <class V, class Row>
requires SameStruct<Row, Interval>
void VisitFields(V& v, Row& r) {
  v(Field("lo").Brief(), r.lo);
  v(Field("hi").Brief(), r.hi);
}

/// WorldCounts' fields.
template <class V, class Row>
requires SameStruct<Row, WorldCounts>
void VisitFields(V& v, Row& r) {
  v(Field("bodies").Brief(), r.bodies);
  v(Field("joints").Brief(), r.joints);
  v(Field("geoms").Brief(), r.geoms);
  v(Field("dynamic_bodies"), r.dynamic_bodies);
}

/// StepStatistics' fields (wall times, s).
template <class V, class Row>
requires SameStruct<Row, StepStatistics>
void VisitFields(V& v, Row& r) {
  v(Field("dynamic_steps").Brief(), r.dynamic_steps);
  v(Field("kinematic_steps").Brief(), r.kinematic_steps);
  v(Field("collision_s"), r.collision_s);
  v(Field("solver_s"), r.solver_s);
  v(Field("control_s"), r.control_s);
  v(Field("max_contacts"), r.max_contacts);
}

/// TrialResult's fields (m, s; the object's final pose in the world), with the keys of the
/// figures every report of a trial carries (a grasp file's validation, graspsynth simulate's
/// nominal trial; each report adds `success` and its own). Its recorded states are not a field:
/// Python shows them as arrays (TrialResult.states).
template <class V, class Row>
requires SameStruct<Row, TrialResult>
void VisitFields(V& v, Row& r) {
  v(Field("outcome").Json("/outcome").Brief(), r.outcome);
  v(Field("reason").Json("/reason"), r.reason);
  v(Field("lift").Json("/lift_m").Brief(), r.lift);
  v(Field("max_lift").Json("/max_lift_m"), r.max_lift);
  v(Field("max_penetration").Json("/max_penetration_m"), r.max_penetration);
  v(Field("simulated_time").Brief(), r.simulated_time);
  v(Field("planned_time"), r.planned_time);
  v(Field("wall_time"), r.wall_time);
  v(Field("cpu_time"), r.cpu_time);
  v(Field("final_object_pose"), r.final_object_pose);
  v(Field("hold"), r.hold);
  v(Field("statistics"), r.statistics);
  v(Field("counts"), r.counts);
}

/// RobustnessTrial's fields: one perturbed replay (m, s).
template <class V, class Row>
requires SameStruct<Row, RobustnessTrial>
void VisitFields(V& v, Row& r) {
  v(Field("index").Brief(), r.index);
  v(Field("time_scale"), r.time_scale);
  v(Field("physics"), r.physics);
  v(Field("outcome").Brief(), r.outcome);
  v(Field("reason"), r.reason);
  v(Field("lift").Brief(), r.lift);
  v(Field("final_object_pose"), r.final_object_pose);
  v(Field("hold"), r.hold);
  v(Field("simulated_time"), r.simulated_time);
  v(Field("wall_time"), r.wall_time);
  v(Field("cpu_time"), r.cpu_time);
  v(Field("dynamic_steps"), r.dynamic_steps);
  v(Field("kinematic_steps"), r.kinematic_steps);
}

/// RobustnessResult's fields: the perturbed replays and their score (s; ci95: Wilson).
template <class V, class Row>
requires SameStruct<Row, RobustnessResult>
void VisitFields(V& v, Row& r) {
  v(Field("trials"), r.trials);
  v(Field("successes").Brief(), r.successes);
  v(Field("score").Brief(), r.score);
  v(Field("ci95").Brief(), r.ci95);
  v(Field("threads"), r.threads);
  v(Field("wall_time"), r.wall_time);
  v(Field("simulated_time"), r.simulated_time);
  v(Field("cpu_time"), r.cpu_time);
}

}  // namespace graspsynth
