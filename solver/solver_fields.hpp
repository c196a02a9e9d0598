#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the synthesis' results that the study's rows
/// carry (why a fallback was used), and the ranges of its enums (methods, statuses, fallback
/// kinds): they drive the job bytes and the Python classes and enums.

#include "common/field_list.hpp"
#include "solver/hold_margin.hpp"
#include "solver/motion_generation.hpp"
#include "solver/synthesis.hpp"

namespace graspsynth {

template <>
struct EnumRange<SynthesisMethod> {
  static constexpr SynthesisMethod kLast = SynthesisMethod::kNearest;
};

template <>
struct EnumRange<SynthesisStatus> {
  static constexpr SynthesisStatus kLast = SynthesisStatus::kUnreachable;
};

template <>
struct EnumRange<FallbackKind> {
  static constexpr FallbackKind kLast = FallbackKind::kPartialBlend;
};

/// FallbackReason's fields (deg, but min_psi_width in rad). The reports write its Text().
template <class V, class Row>
requires SameStruct<Row, FallbackReason>
void VisitFields(V& v, Row& r) {
  v(Field("kind").Brief(), r.kind);
  v(Field("bracket_reason").Brief(), r.bracket_reason);
  v(Field("lower_deg"), r.lower_deg);
  v(Field("upper_deg"), r.upper_deg);
  v(Field("used_deg"), r.used_deg);
  v(Field("robust"), r.robust);
  v(Field("min_psi_width"), r.min_psi_width);
  v(Field("line_unreachable"), r.line_unreachable);
  v(Field("side"), r.side);
  v(Field("blend_failed"), r.blend_failed);
  v(Field("cell"), r.cell);
  v(Field("used_placement"), r.used_placement);
}

/// HoldMargin's fields (mm, deg, object weights; contacts and load_share: the groups of
/// kLoadShareGroups, fingers then palm). The reports write HoldMarginJson.
template <class V, class Row>
requires SameStruct<Row, HoldMargin>
void VisitFields(V& v, Row& r) {
  v(Field("measured"), r.measured);
  v(Field("slip_mm").Brief(), r.slip_mm);
  v(Field("slip_deg").Brief(), r.slip_deg);
  v(Field("end_tilt_deg"), r.end_tilt_deg);
  v(Field("contacts"), r.contacts);
  v(Field("load_share"), r.load_share);
  v(Field("load_bearing_links").Brief(), r.load_bearing_links);
  v(Field("fingertips_only"), r.fingertips_only);
  v(Field("epsilon_weight").Brief(), r.epsilon_weight);
  v(Field("torque_scale_m"), r.torque_scale_m);
  v(Field("friction_use_max").Brief(), r.friction_use_max);
  v(Field("friction_use_mean"), r.friction_use_mean);
  v(Field("normal_force_weight"), r.normal_force_weight);
}

}  // namespace graspsynth
