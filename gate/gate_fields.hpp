#pragma once

/// @file
/// The field list (common/field_list.hpp) of the gate's result that the study's rows carry (the
/// nominal hold's margin): it drives the job bytes and the Python class.

#include "common/field_list.hpp"
#include "gate/hold_margin.hpp"

namespace graspsynth {

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
