#pragma once

/// @file
/// The options of the hold margin (gate/hold_margin.hpp) for every request whose grasps go
/// through the physics gate or whose trial reports the margin (synthesize, generalize, run,
/// simulate): whether the gate requires it, and its thresholds. The thresholds' help is their
/// reason (HoldMarginThresholds), and their ranges are HoldMarginOptions::IsValid's.

#include <cctype>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "gate/hold_margin.hpp"
#include "request/option.hpp"

namespace graspsynth::request {

/// The help heading of the hold margin's options.
inline constexpr const char* kHoldMarginGroup =
    "Hold margin (how securely the nominal trial holds the object at the end of its hold)";

/// The hold margin's options of request type R, reading and writing the HoldMarginOptions that
/// `ref` returns (`[](R& r) -> HoldMarginOptions& { return r.gate.hold_margin; }`).
template <class R, class F>
OptionList<R> HoldMarginOptionList(F ref) {
  using H = HoldMarginOptions;
  OptionList<R> list;
  OptionInfo require = MakeInfo(
      "require_hold_margin", OptionKind::kBool,
      "The physics gate fails a grasp whose nominal hold misses a hold-margin threshold (default: "
      "the margin is reported only; simulate exits 1)");
  require.group = kHoldMarginGroup;
  list.push_back(FieldOption<R>(require, [ref](R& r) -> bool& { return ref(r).require; }));
  // the thresholds' help is their reason, as the reports state it.
  const std::vector<HoldMarginThreshold> reasons = HoldMarginThresholds(H{});
  const auto help = [&](const char* name) {
    for (const HoldMarginThreshold& t : reasons) {
      if (t.name == name)
        return std::string(1, static_cast<char>(std::toupper(t.reason[0]))) + t.reason.substr(1);
    }
    return std::string();
  };
  const auto number = [&](const char* name, double H::*field, double lo, bool lo_open, double hi) {
    OptionInfo info = WithRange(MakeInfo(name, OptionKind::kNumber, help(name)), lo, hi, lo_open);
    info.group = kHoldMarginGroup;
    list.push_back(FieldOption<R>(info, [ref, field](R& r) -> double& { return ref(r).*field; }));
  };
  number("max_slip_mm", &H::max_slip_mm, 0.0, true, INFINITY);
  number("max_slip_deg", &H::max_slip_deg, 0.0, true, 180.0);
  number("min_epsilon_weight", &H::min_epsilon_weight, 0.0, false, INFINITY);
  OptionInfo links = WithRange(
      MakeInfo("min_load_bearing_links", OptionKind::kInt, help("min_load_bearing_links")), 0,
      kMaxLoadBearingLinks);
  links.group = kHoldMarginGroup;
  list.push_back(
      FieldOption<R>(links, [ref](R& r) -> int& { return ref(r).min_load_bearing_links; }));
  number("max_friction_use_mean", &H::max_friction_use_mean, 0.0, true, INFINITY);
  return list;
}

/// Appends HoldMarginOptionList<R>(ref) to `list`.
template <class R, class F>
void AppendHoldMarginOptions(F ref, OptionList<R>* list) {
  for (Option<R>& o : HoldMarginOptionList<R>(ref)) list->push_back(std::move(o));
}

}  // namespace graspsynth::request
