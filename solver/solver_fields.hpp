#pragma once

/// @file
/// The field lists (common/field_list.hpp) of the synthesis' results that the study's rows
/// carry (why a fallback was used), and the ranges of its enums (methods, statuses, fallback
/// kinds): they drive the job bytes and the Python classes and enums.

#include "common/field_list.hpp"
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

}  // namespace graspsynth
