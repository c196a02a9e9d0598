#include "gate/hold_margin.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "common/demand.hpp"
#include "common/format.hpp"

namespace graspsynth {
namespace {

// a contact below this share of the summed force magnitudes carries no load (contact noise).
constexpr double kLoadBearingContact = 0.01;
// a link carries load from this share of the summed force magnitudes on (LoadBearers' share).
constexpr double kLoadBearingLink = 0.1;
// friction use is capped here: a contact that rubs without pushing has no finite use.
constexpr double kMaxFrictionUse = 10.0;

// whether a hand link index (HandJointVector order; the joint count for the palm and mount) is
// a fingertip: its finger's distal link.
bool IsFingertip(const HandModel& hand, int hand_link) {
  return hand_link >= 0 && hand_link < hand.joint_count() && hand.is_distal(hand_link);
}

// the links' share of the force and whether each carrying one is a fingertip.
void MeasureLinks(const HandModel& hand, const std::vector<HandObjectContact>& contacts,
                  double total, HoldMargin* m) {
  std::map<int, double> per_link;
  for (const HandObjectContact& c : contacts) per_link[c.hand_link] += c.f_W.norm();
  bool all_tips = true;
  for (const auto& [link, force] : per_link) {
    if (force < kLoadBearingLink * total) continue;
    ++m->load_bearing_links;
    all_tips = all_tips && IsFingertip(hand, link);
  }
  m->fingertips_only = m->load_bearing_links > 0 && all_tips;
}

}  // namespace

bool HoldMarginOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what, double v) {
    if (why) *why = std::string("hold margin: ") + what + " = " + Format("%g", v);
    return false;
  };
  if (!(std::isfinite(max_slip_mm) && max_slip_mm > 0.0)) {
    return fail("max_slip_mm (mm, > 0)", max_slip_mm);
  }
  if (!(std::isfinite(max_slip_deg) && max_slip_deg > 0.0 && max_slip_deg <= 180.0)) {
    return fail("max_slip_deg (deg, in (0, 180])", max_slip_deg);
  }
  if (!(std::isfinite(min_epsilon_weight) && min_epsilon_weight >= 0.0)) {
    return fail("min_epsilon_weight (>= 0)", min_epsilon_weight);
  }
  if (min_load_bearing_links < 0 || min_load_bearing_links > kMaxLoadBearingLinks) {
    return fail("min_load_bearing_links (in [0, 21])", min_load_bearing_links);
  }
  if (!(std::isfinite(max_friction_use_mean) && max_friction_use_mean > 0.0)) {
    return fail("max_friction_use_mean (> 0)", max_friction_use_mean);
  }
  return true;
}

std::vector<HoldMarginThreshold> HoldMarginThresholds(const HoldMarginOptions& o) {
  return {
      {"max_slip_mm", o.max_slip_mm,
       "largest slip of the object in the hand from lift-off to the end, mm: above every pan-study "
       "grasp (up to 38.7 mm), since ODE's slip did not tell the grasps MuJoCo drops from those it "
       "holds (6 of the 10 that hold in MuJoCo slip over 20 mm in ODE); it bounds a hold that "
       "slides along the handle"},
      {"max_slip_deg", o.max_slip_deg,
       "largest rotation of the object in the hand, deg: above every pan-study grasp (up to "
       "6.7 deg); a pan that turns more pivots about its grip"},
      {"min_epsilon_weight", o.min_epsilon_weight,
       "smallest Ferrari-Canny epsilon of the contacts at their measured normal forces, in object "
       "weights: the 3 pan-study grasps below 0.05 that ODE lifts all fail their hold in MuJoCo, "
       "and none that holds in MuJoCo is below 0.08"},
      {"min_load_bearing_links", static_cast<double>(o.min_load_bearing_links),
       "fewest hand links carrying 10% of the contact force or more: one link alone holds by "
       "friction at a point (every pan-study grasp has 3 or more)"},
      {"max_friction_use_mean", o.max_friction_use_mean,
       "largest force-weighted mean |f_t| / (mu f_n) of the load-bearing contacts: beyond 1 the "
       "hold leans on friction outside the Coulomb cone, which ODE's solve can leave and MuJoCo "
       "does not give (6 of the 13 pan-study grasps that fail their hold in MuJoCo are beyond it, "
       "1 of the 10 that hold)"},
  };
}

HoldMargin MeasureHoldMargin(const SimulationModel& model, const TrialResult& trial,
                             const GraspQualityOptions& quality) {
  HoldMargin m;
  const HoldQuality& h = trial.hold;
  m.slip_mm = h.slip * 1e3;
  m.slip_deg = h.slip_angle / kDeg;
  m.end_tilt_deg = h.end_tilt / kDeg;
  m.load_share = h.load_share;
  double total = 0.0;
  for (const HandObjectContact& c : trial.end_contacts) {
    const int group = LoadShareGroup(model.robot().hand, c.hand_link);
    GS_DEMAND(group >= 0, "a hand link outside the load share's groups");
    ++m.contacts[static_cast<size_t>(group)];
    total += c.f_W.norm();
  }
  const double weight = model.object_inertia().mass * model.options().gravity;
  if (trial.end_contacts.empty() || total <= 0.0 || weight <= 0.0) return m;
  m.measured = true;
  MeasureLinks(model.robot().hand, trial.end_contacts, total, &m);

  // the load-bearing contacts: their friction use and their force-scaled cones (a cone of
  // almost no normal force adds a sliver of wrenches that only blurs the hull).
  double normal_sum = 0.0;
  for (const HandObjectContact& c : trial.end_contacts) {
    normal_sum += std::max(0.0, c.f_W.dot(c.n_W));
  }
  std::vector<GraspContact> cones;
  double use_weighted = 0.0, weights = 0.0;
  for (const HandObjectContact& c : trial.end_contacts) {
    const double f = c.f_W.norm();
    if (f < kLoadBearingContact * total) continue;
    const double fn = std::max(0.0, c.f_W.dot(c.n_W));
    const double ft = (c.f_W - c.f_W.dot(c.n_W) * c.n_W).norm();
    // a contact that rubs without pushing (ODE's Dantzig solve can leave one so) is past the
    // cone's edge however little it pushes: the cap.
    const double use =
        ft < kMaxFrictionUse * c.friction * fn ? ft / (c.friction * fn) : kMaxFrictionUse;
    m.friction_use_max = std::max(m.friction_use_max, use);
    use_weighted += f * use;
    weights += f;
    if (fn >= kLoadBearingContact * normal_sum) cones.push_back({c.p_WC, c.n_W, c.friction, fn});
  }
  m.friction_use_mean = weights > 0.0 ? use_weighted / weights : 0.0;
  m.normal_force_weight = normal_sum / weight;

  const Eigen::Vector3d p_WC = trial.final_object_pose * model.object_inertia().p_OC;
  const GraspQuality q = EvaluateGraspQuality(cones, p_WC, quality);
  m.torque_scale_m = q.torque_scale;
  // no finite facet distance (a hull whose every facet is flat) is no measured margin.
  m.epsilon_weight = std::isfinite(q.epsilon) ? std::max(0.0, q.epsilon) / weight : 0.0;
  return m;
}

std::string HoldMarginBrief(const HoldMargin& m) {
  if (!m.measured) return "not measured (no contact force at the end of the trial)";
  return Format(
      "slip %.1f mm, %.1f deg; end tilt %.1f deg; %d load-bearing links%s; epsilon %.3g "
      "weights; friction use %.2f (mean %.2f); squeeze %.2f weights",
      m.slip_mm, m.slip_deg, m.end_tilt_deg, m.load_bearing_links,
      m.fingertips_only ? " (fingertips only)" : "", m.epsilon_weight, m.friction_use_max,
      m.friction_use_mean, m.normal_force_weight);
}

std::string HoldMarginShortfall(const HoldMargin& m, const HoldMarginOptions& o) {
  if (!m.measured) return "not measured (no contact force at the end of the trial)";
  std::vector<std::string> misses;
  if (m.slip_mm > o.max_slip_mm) {
    misses.push_back(Format("slip %.1f mm > %g mm", m.slip_mm, o.max_slip_mm));
  }
  if (m.slip_deg > o.max_slip_deg) {
    misses.push_back(Format("slip %.1f deg > %g deg", m.slip_deg, o.max_slip_deg));
  }
  if (m.epsilon_weight < o.min_epsilon_weight) {
    misses.push_back(
        Format("epsilon %.3g weights < %g weights", m.epsilon_weight, o.min_epsilon_weight));
  }
  if (m.load_bearing_links < o.min_load_bearing_links) {
    misses.push_back(
        Format("%d load-bearing links < %d", m.load_bearing_links, o.min_load_bearing_links));
  }
  if (m.friction_use_mean > o.max_friction_use_mean) {
    misses.push_back(
        Format("friction use mean %.2f > %g", m.friction_use_mean, o.max_friction_use_mean));
  }
  std::string text;
  for (const std::string& s : misses) text += (text.empty() ? "" : "; ") + s;
  return text;
}

}  // namespace graspsynth
