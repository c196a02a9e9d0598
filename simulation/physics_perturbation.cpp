#include "simulation/physics_perturbation.hpp"

#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "common/valid_options.hpp"
#include "simulation/random.hpp"

namespace graspsynth {
namespace {

bool Check(bool ok, const char* what, double value, std::string* why) {
  if (!ok && why) {
    std::ostringstream s;
    s << "physics perturbation " << what << " = " << value;
    *why = s.str();
  }
  return ok;
}

bool HalfRange(double x) { return std::isfinite(x) && x >= 0.0 && x < 1.0; }
bool FactorRange(double lo, double hi) {
  return std::isfinite(lo) && std::isfinite(hi) && lo > 0.0 && hi >= lo;
}

double LogUniform(SplitMix64& rng, double lo, double hi) {
  return std::exp(rng.Uniform(std::log(lo), std::log(hi)));
}

void Validate(const PhysicsPerturbationOptions& options) {
  RequireValid(options, "invalid option");
}

}  // namespace

bool PhysicsPerturbationOptions::IsValid(std::string* why) const {
  return Check(HalfRange(friction), "friction (half-range, [0, 1))", friction, why) &&
         Check(FactorRange(stiffness_min, stiffness_max), "stiffness_min (0 < min <= max)",
               stiffness_min, why) &&
         Check(FactorRange(damping_min, damping_max), "damping_min (0 < min <= max)", damping_min,
               why) &&
         Check(HalfRange(mass), "mass (half-range, [0, 1))", mass, why) &&
         Check(std::isfinite(com_offset) && com_offset >= 0.0 && com_offset <= 0.02,
               "com_offset (m, [0, 0.02])", com_offset, why) &&
         Check(HalfRange(servo_force), "servo_force (half-range, [0, 1))", servo_force, why) &&
         Check(std::isfinite(fine_step) && fine_step > 0.0 && fine_step <= 0.02,
               "fine_step (s, (0, 0.02])", fine_step, why) &&
         Check(std::isfinite(fine_step_probability) && fine_step_probability >= 0.0 &&
                   fine_step_probability <= 1.0,
               "fine_step_probability ([0, 1])", fine_step_probability, why);
}

PhysicsDraw DrawPhysics(const PhysicsPerturbationOptions& options, SplitMix64& rng) {
  Validate(options);
  PhysicsDraw d;
  if (!options.enabled) return d;
  PhysicsVariation& v = d.variation;
  v.object_hand_friction = rng.Uniform(1.0 - options.friction, 1.0 + options.friction);
  v.object_table_friction = rng.Uniform(1.0 - options.friction, 1.0 + options.friction);
  v.contact_stiffness = LogUniform(rng, options.stiffness_min, options.stiffness_max);
  v.contact_damping = LogUniform(rng, options.damping_min, options.damping_max);
  v.object_mass = rng.Uniform(1.0 - options.mass, 1.0 + options.mass);
  for (int i = 0; i < 3; ++i) {
    v.object_com_offset[i] = rng.Uniform(-options.com_offset, options.com_offset);
  }
  v.hand_effort = rng.Uniform(1.0 - options.servo_force, 1.0 + options.servo_force);
  if (rng.Uniform() < options.fine_step_probability) d.time_step = options.fine_step;
  return d;
}

const std::vector<PhysicsFactor>& AllPhysicsFactors() {
  static const std::vector<PhysicsFactor> all = {
      PhysicsFactor::kHandFriction, PhysicsFactor::kTableFriction, PhysicsFactor::kStiffness,
      PhysicsFactor::kDamping,      PhysicsFactor::kMass,          PhysicsFactor::kCenterOfMass,
      PhysicsFactor::kServoForce,   PhysicsFactor::kStep};
  return all;
}

std::string_view ToString(PhysicsFactor factor) {
  switch (factor) {
    case PhysicsFactor::kHandFriction:
      return "hand_friction";
    case PhysicsFactor::kTableFriction:
      return "table_friction";
    case PhysicsFactor::kStiffness:
      return "contact_stiffness";
    case PhysicsFactor::kDamping:
      return "contact_damping";
    case PhysicsFactor::kMass:
      return "object_mass";
    case PhysicsFactor::kCenterOfMass:
      return "center_of_mass";
    case PhysicsFactor::kServoForce:
      return "servo_force";
    case PhysicsFactor::kStep:
      return "step";
  }
  return "unknown";
}

PhysicsDraw PhysicsAtEnd(const PhysicsPerturbationOptions& options, PhysicsFactor factor, bool high,
                         const Eigen::Vector3d& com_direction_O) {
  Validate(options);
  const double sign = high ? 1.0 : -1.0;
  PhysicsDraw d;
  PhysicsVariation& v = d.variation;
  switch (factor) {
    case PhysicsFactor::kHandFriction:
      v.object_hand_friction = 1.0 + sign * options.friction;
      break;
    case PhysicsFactor::kTableFriction:
      v.object_table_friction = 1.0 + sign * options.friction;
      break;
    case PhysicsFactor::kStiffness:
      v.contact_stiffness = high ? options.stiffness_max : options.stiffness_min;
      break;
    case PhysicsFactor::kDamping:
      v.contact_damping = high ? options.damping_max : options.damping_min;
      break;
    case PhysicsFactor::kMass:
      v.object_mass = 1.0 + sign * options.mass;
      break;
    case PhysicsFactor::kCenterOfMass:
      if (com_direction_O.allFinite() && com_direction_O.norm() > 1e-12) {
        v.object_com_offset = sign * options.com_offset * com_direction_O.normalized();
      }
      break;
    case PhysicsFactor::kServoForce:
      v.hand_effort = 1.0 + sign * options.servo_force;
      break;
    case PhysicsFactor::kStep:
      if (high) d.time_step = options.fine_step;
      break;
  }
  return d;
}

Eigen::Vector3d SensitivityComDirection(const SimulationModel& model) {
  const Eigen::Vector3d& c = model.object_inertia().p_OC;
  return c.norm() > 1e-9 ? Eigen::Vector3d(c.normalized()) : Eigen::Vector3d::UnitX();
}

}  // namespace graspsynth
