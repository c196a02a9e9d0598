#pragma once

/// @file
/// The JSON of a trial's hold quality, a replay's physics and a sensitivity table, shared by the
/// reports that carry them (graspsynth-simulation/1, graspsynth-study-synthesis/1 and
/// graspsynth-generalization/1; docs/formats.md). Templates over nlohmann's json types, so that
/// a report keeps its own key order. Numbers are rounded to 1e-9.

#include <cmath>
#include <string>

#include "kinematics/hand_model.hpp"
#include "kinematics/types.hpp"
#include "simulation/robustness.hpp"

namespace graspsynth {

/// x rounded to 1e-9 (the reports' figures are physical; -0 becomes 0).
inline double RoundForReport(double x) {
  const double r = std::round(x * 1e9) / 1e9;
  return r == 0.0 ? 0.0 : r;
}

/// {end_tilt_deg, max_tilt_deg, slip_m, slip_deg, contacts, load_bearers, load_share {finger:
/// share, ..., palm}}.
template <class Json>
Json HoldQualityJson(const HoldQuality& h) {
  Json share = Json::object();
  for (size_t k = 0; k < kLoadShareGroups.size(); ++k) {
    share[std::string(kLoadShareGroups[k])] = RoundForReport(h.load_share[k]);
  }
  return Json{{"end_tilt_deg", RoundForReport(h.end_tilt / kDeg)},
              {"max_tilt_deg", RoundForReport(h.max_tilt / kDeg)},
              {"slip_m", RoundForReport(h.slip)},
              {"slip_deg", RoundForReport(h.slip_angle / kDeg)},
              {"contacts", h.contacts},
              {"load_bearers", h.LoadBearers()},
              {"load_share", share}};
}

/// The factors of a replay's physics and its step (`default_step` when it kept the trial's).
template <class Json>
Json PhysicsDrawJson(const PhysicsDraw& d, double default_step) {
  const PhysicsVariation& v = d.variation;
  const Eigen::Vector3d& c = v.object_com_offset;
  return Json{
      {"hand_friction", RoundForReport(v.object_hand_friction)},
      {"table_friction", RoundForReport(v.object_table_friction)},
      {"contact_stiffness", RoundForReport(v.contact_stiffness)},
      {"contact_damping", RoundForReport(v.contact_damping)},
      {"object_mass", RoundForReport(v.object_mass)},
      {"com_offset_m", {RoundForReport(c.x()), RoundForReport(c.y()), RoundForReport(c.z())}},
      {"servo_force", RoundForReport(v.hand_effort)},
      {"time_step_s", d.time_step > 0.0 ? d.time_step : default_step}};
}

/// {trials_per_end, factors: [{factor, low: {physics, successes, failures}, high: {...}}]}.
template <class Json>
Json SensitivityJson(const SensitivityResult& s, double default_step) {
  Json factors = Json::array();
  const auto cell_json = [&](const SensitivityCell& cell) {
    return Json{{"physics", PhysicsDrawJson<Json>(cell.physics, default_step)},
                {"successes", cell.successes},
                {"failures", cell.failures}};
  };
  for (const SensitivityRow& row : s.rows) {
    Json f;
    f["factor"] = std::string(ToString(row.factor));
    f["low"] = cell_json(row.low);
    f["high"] = cell_json(row.high);
    factors.push_back(f);
  }
  return Json{{"trials_per_end", s.trials_per_cell}, {"factors", factors}};
}

}  // namespace graspsynth
