#pragma once

/// @file
/// The options of the physics: the fallback of a blend that fails in physics, and the options
/// of the physics perturbation (simulation/physics_perturbation.hpp), for every request whose
/// replays draw their physics: physics on|off, the friction, mass and servo
/// force spreads, the contact stiffness and damping ranges, the centre-of-mass offset and the
/// fine step. Their ranges are PhysicsPerturbationOptions::IsValid's.

#include <utility>

#include "request/option.hpp"
#include "simulation/physics_perturbation.hpp"

namespace graspsynth::request {

/// The help heading of the physics perturbation's options.
inline constexpr const char* kPhysicsGroup =
    "Physics perturbation (each perturbed replay draws its physics)";

/// The physics perturbation's options of request type R, reading and writing the
/// PhysicsPerturbationOptions that `ref` returns (`[](R& r) -> PhysicsPerturbationOptions& {
/// return r.gate.robustness.perturbation.physics; }`).
template <class R, class F>
OptionList<R> PhysicsOptions(F ref) {
  using P = PhysicsPerturbationOptions;
  OptionList<R> list;
  const auto number = [&](const char* name, double P::*field, double lo, bool lo_open, double hi,
                          bool hi_open, const char* help) {
    OptionInfo info = MakeInfo(name, OptionKind::kNumber, help);
    info.lo = lo;
    info.lo_open = lo_open;
    info.hi = hi;
    info.hi_open = hi_open;
    info.group = kPhysicsGroup;
    list.push_back(FieldOption<R>(info, [ref, field](R& r) -> double& { return ref(r).*field; }));
  };
  const auto range = [&](const char* name, double P::*lo, double P::*hi, const char* what) {
    Option<R> o;
    o.info = MakeInfo(name, OptionKind::kNumberPair,
                      std::string("Contact ") + what + ": the range of its factor (log-uniform)");
    o.info.group = kPhysicsGroup;
    o.get = [ref, lo, hi](const R& r) -> Value {
      const P& p = ref(const_cast<R&>(r));
      return std::vector<double>{p.*lo, p.*hi};
    };
    o.set = [ref, lo, hi](R& r, const Value& v) {
      const auto& pair = std::get<std::vector<double>>(v);
      ref(r).*lo = pair[0];
      ref(r).*hi = pair[1];
    };
    list.push_back(std::move(o));
  };
  OptionInfo physics =
      MakeInfo("physics", OptionKind::kBool,
               "on: every perturbed replay also draws friction, contact stiffness and damping, the "
               "object's mass and centre of mass, the finger servos' force and the step; off: the "
               "modelled physics only");
  physics.on_off = true;
  physics.group = kPhysicsGroup;
  list.push_back(FieldOption<R>(physics, [ref](R& r) -> bool& { return ref(r).enabled; }));
  number("friction_spread", &P::friction, 0.0, false, 1.0, true,
         "Relative half-range of the object-hand and object-table friction");
  range("stiffness_range", &P::stiffness_min, &P::stiffness_max, "stiffness");
  range("damping_range", &P::damping_min, &P::damping_max, "damping");
  number("mass_spread", &P::mass, 0.0, false, 1.0, true,
         "Relative half-range of the object's mass");
  number("com_offset", &P::com_offset, 0.0, false, 0.02, false,
         "Half-range of the object's centre of mass per axis, m");
  number("servo_force_spread", &P::servo_force, 0.0, false, 1.0, true,
         "Relative half-range of the finger servos' force caps");
  number("fine_step", &P::fine_step, 0.0, true, 0.02, false, "The alternative physics step, s");
  number("fine_step_probability", &P::fine_step_probability, 0.0, false, 1.0, false,
         "Chance that a replay runs at fine_step instead of the trial's step");
  return list;
}

/// Appends PhysicsOptions<R>(ref) to `list`.
template <class R, class F>
void AppendPhysicsOptions(F ref, OptionList<R>* list) {
  for (Option<R>& o : PhysicsOptions<R>(ref)) list->push_back(std::move(o));
}

/// The option physics_fallback (ValidatedSynthesisOptions::physics_fallback) of request type
/// R, reading and writing the bool that `ref` returns.
template <class R, class F>
Option<R> PhysicsFallbackOption(F ref) {
  return FieldOption<R>(
      MakeInfo("physics_fallback", OptionKind::kBool,
               "An interp blend whose nominal trial fails in physics gives way to the fallbacks "
               "of a bracket that cannot be blended, the nearer demonstration turned with the "
               "object first"),
      ref);
}

/// The option all_replays of request type R: every selection replay of every demonstration.
/// It reads and writes the bool that `ref` returns: SelectionOptions::early_stop, its negation,
/// with `inverted` (`[](R& r) -> bool& { return r.selection.early_stop; }`), or the request's
/// own all_replays without.
template <class R, class F>
Option<R> AllReplaysOption(F ref, bool inverted) {
  Option<R> o;
  o.info = MakeInfo("all_replays", OptionKind::kBool,
                    "Run every selection replay of every demonstration (default: a demonstration "
                    "stops replaying once it has failed too often to win its orientation; the "
                    "representatives and their scores are the same, the losers' scores count "
                    "fewer replays)");
  o.get = [ref, inverted](const R& r) -> Value { return ref(const_cast<R&>(r)) != inverted; };
  o.set = [ref, inverted](R& r, const Value& v) { ref(r) = std::get<bool>(v) != inverted; };
  return o;
}

}  // namespace graspsynth::request
