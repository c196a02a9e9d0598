#pragma once

/// @file
/// Perturbed physics of a replay, for robustness evaluation: a grasp must hold under the range
/// of contact models and objects it may meet, not only under the one that was modelled.
///
/// Each replay draws, from its own random stream after the motion's draws
/// (simulation/perturbation.hpp), in this order:
/// 1. the object-hand friction factor ~ U[1 - friction, 1 + friction];
/// 2. the object-table friction factor ~ U[1 - friction, 1 + friction];
/// 3. the contact stiffness factor, log-uniform in [stiffness_min, stiffness_max];
/// 4. the contact damping factor, log-uniform in [damping_min, damping_max];
/// 5. the object's mass factor ~ U[1 - mass, 1 + mass] (inertia scaled with it);
/// 6. the centre-of-mass offset, each object-frame axis ~ U[-com_offset, com_offset];
/// 7. the finger servos' force-cap factor ~ U[1 - servo_force, 1 + servo_force];
/// 8. the step: fine_step with probability fine_step_probability, else the trial's own step.
/// Every draw is made whatever the ranges (a zero range gives the nominal value), so one range's
/// change never shifts another's values.
///
/// The default ranges and their reasons (docs/architecture.md, "Robustness under the contact
/// model"):
/// - friction +-25%: Coulomb coefficients of rubber-like fingertips on metal or plastic are
///   measured within about that of a nominal value, and they change with wear and dirt;
/// - stiffness and damping x0.5 to x2: soft-contact parameters are a modelling choice, not a
///   measurement; a factor of two either way spans the values that hold the grasp's contacts
///   stable at both steps (reference/ode.md);
/// - mass +-20% and centre of mass +-1 cm: the same pan with or without contents, a lid or a
///   thicker base;
/// - servo force +-20%: motor torque constants, current limits and gear efficiency vary by
///   about that between units and with temperature;
/// - the step, the fast one or 1 ms: a grasp must not depend on the integrator's step.

#include <string>
#include <string_view>
#include <vector>

#include "simulation/simulation_model.hpp"

namespace graspsynth {

class SplitMix64;

/// Ranges of the physics a perturbed replay draws (see the file comment).
struct PhysicsPerturbationOptions {
  bool enabled = true;         ///< false: every replay has the modelled physics, nothing drawn
  double friction = 0.25;      ///< relative half-range of both friction factors, [0, 1)
  double stiffness_min = 0.5;  ///< contact stiffness factor range, 0 < min <= max
  double stiffness_max = 2.0;  ///<
  double damping_min = 0.5;    ///< contact damping factor range, 0 < min <= max
  double damping_max = 2.0;    ///<
  double mass = 0.2;           ///< relative half-range of the object's mass, [0, 1)
  double com_offset = 0.01;    ///< m, half-range per object-frame axis, [0, 0.02]
  double servo_force = 0.2;    ///< relative half-range of the finger force caps, [0, 1)
  double fine_step = 0.001;    ///< s, the alternative step, (0, 0.02]
  double fine_step_probability = 0.5;  ///< chance of the alternative step, [0, 1]

  bool IsValid(std::string* why) const;
};

/// The physics of one replay: the variation of the world and the step.
struct PhysicsDraw {
  PhysicsVariation variation;
  double time_step = 0.0;  ///< s; 0: the trial's own step
};

/// Draws one replay's physics from `rng` (see the file comment); the modelled physics, without
/// drawing, when the options are disabled. Throws InputError for invalid options.
PhysicsDraw DrawPhysics(const PhysicsPerturbationOptions& options, SplitMix64& rng);

/// A factor of the physics perturbation, for the sensitivity of a grasp to each alone.
enum class PhysicsFactor {
  kHandFriction,   ///< object-hand friction
  kTableFriction,  ///< object-table friction
  kStiffness,      ///< contact stiffness
  kDamping,        ///< contact damping
  kMass,           ///< object mass
  kCenterOfMass,   ///< centre of mass along com_direction
  kServoForce,     ///< finger servo force caps
  kStep,           ///< the step (low end: the trial's own; high end: fine_step)
};

/// Every factor, in the enum's order.
const std::vector<PhysicsFactor>& AllPhysicsFactors();

/// Lowercase name of a factor, e.g. "hand_friction" (report files use it).
std::string_view ToString(PhysicsFactor factor);

/// The physics with `factor` alone at the low or the high end of its range and everything else
/// as modelled. The centre of mass moves along the unit vector `com_direction_O` (object
/// frame): by -com_offset at the low end and +com_offset at the high end. Throws InputError
/// for invalid options.
PhysicsDraw PhysicsAtEnd(const PhysicsPerturbationOptions& options, PhysicsFactor factor, bool high,
                         const Eigen::Vector3d& com_direction_O);

/// The direction along which the sensitivity moves the centre of mass: from the object frame's
/// origin to the modelled centre of mass (for the pan, towards its handle), or the object's x
/// axis when they coincide.
Eigen::Vector3d SensitivityComDirection(const SimulationModel& model);

}  // namespace graspsynth
