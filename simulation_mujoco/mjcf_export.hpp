#pragma once

/// @file
/// The grasp scene as an MJCF model for MuJoCo (docs/mujoco.md): the PA-10 arm and the Gifu
/// Hand III of the robot description, the table, the object (its primitives, its meshes as mesh
/// assets) at a placement, servo actuators for every arm and hand joint with the description's
/// limits and force caps, and the contact settings that mirror the ODE world's
/// (SimulationOptions). Writing the text needs no MuJoCo library; loading it does
/// (simulation_mujoco/mujoco_world.hpp).
///
/// Names in the model: every body, joint and actuator takes the robot description's link or
/// joint name (the DIP joints too: each has an actuator whose target is its PIP's angle, as the
/// ODE controller drives them); the object is the body "object" on the free joint "object"; the
/// table is the geom "table". Geoms are "<body>/<k>".
///
/// The servos: every joint has a position actuator with a damping term in its bias (MuJoCo's
/// general actuator, affine bias): force = kp (ctrl - q) - kv qdot, capped at the joint's
/// effort, with kp = gain kv (gain: SimulationOptions' servo gain, 20 1/s). Setting
/// ctrl = q + v / gain makes it ODE's velocity servo, force = kv (v - qdot) within the cap, with
/// the finite gain kv instead of ODE's hard constraint (MujocoServo); setting ctrl to a target
/// angle makes it a capped PD servo towards it (how a MuJoCo user plays the keyframes).

#include <string>
#include <string_view>
#include <vector>

#include "motion/joint_trajectory.hpp"
#include "simulation/simulation_model.hpp"

namespace graspsynth {

/// How ODE's finger servo (a velocity motor that is a hard constraint up to its force cap) is
/// mapped onto a MuJoCo actuator of finite gain: kv = effort / v_sat, where v_sat is the
/// velocity error at which the servo reaches its cap.
enum class MujocoServo {
  kStiff,  ///< v_sat = 0.01 rad/s: the cap is reached at 0.5 mrad of position error
  kSoft,   ///< v_sat = 0.5 rad/s: the cap is reached at 25 mrad (1.4 deg) of position error
};

/// "stiff" or "soft".
std::string_view ToString(MujocoServo servo);
/// The servo of "stiff" or "soft"; throws InputError naming `what` and the value otherwise.
MujocoServo ParseMujocoServo(std::string_view text, std::string_view what);
/// The velocity error (rad/s) at which a servo of this mapping reaches its force cap.
double SaturationVelocity(MujocoServo servo);

/// MuJoCo's own contact settings of the exported model, beyond the mapping of ODE's
/// (docs/mujoco.md, "Contacts"); the defaults are that mapping. The MuJoCo sweep
/// (simulation_mujoco/mujoco_sweep.hpp) changes them one at a time.
struct MjcfContact {
  /// Factor on solref's time constant (the mapped sqrt(m / kp), after MuJoCo's floor of two
  /// steps), > 0: 2 makes every contact's reference twice as slow (softer).
  double time_constant_scale = 1.0;
  /// solimp's dmin, dmax (in (0, 1), dmin <= dmax) and width (m, > 0): the impedance at zero
  /// and at full penetration and the penetration between them.
  double solimp_dmin = 0.95, solimp_dmax = 0.99, solimp_width = 0.001;
  bool pyramidal = false;  ///< cone="pyramidal" instead of "elliptic"
  double impratio = 10.0;  ///< friction's impedance over the normal's, >= 1 (MuJoCo's impratio)

  /// True when every value is finite and in its range.
  bool IsValid(std::string* why) const;
};

/// Options of the exported model.
struct MjcfOptions {
  double time_step = 0.001;  ///< MuJoCo's step, s
  /// The hand's servo mapping (the arm's servos are always kStiff: ODE's fast trials move the
  /// arm kinematically).
  MujocoServo servo = MujocoServo::kStiff;
  /// Changes of the physics (friction, contact stiffness and damping, the object's mass and
  /// centre of mass, the finger servos' force caps), as the ODE world applies them.
  PhysicsVariation physics;
  /// MuJoCo's contact settings (solref's time constant, solimp, the cone, impratio).
  MjcfContact contact;

  /// True when the step is finite and in (0, 0.02] s and the variation and contact valid.
  bool IsValid(std::string* why) const;
};

/// What a geom of the exported model is, for the contact report.
enum class MjcfRole { kTable, kObject, kArm, kPalm, kFinger };

/// One collision geom of the exported model.
struct MjcfGeom {
  std::string name;
  MjcfRole role = MjcfRole::kTable;
  std::string link;     ///< the robot link (or "table", or the object's name)
  int hand_index = -1;  ///< finger link's HandJointVector index; the hand's joint count for
                        ///< the palm and mount
};

/// The exported model: the MJCF text and its collision geoms.
struct MjcfModel {
  std::string xml;
  std::vector<MjcfGeom> geoms;
};

/// The model of `model`'s robot and scene with the object at `placement`, the robot at the
/// first sample of `trajectory` (or at zero without one) and, with a trajectory, one keyframe
/// per trajectory sample (docs/mujoco.md, "Keyframes"). Throws InputError for invalid options.
MjcfModel ExportMjcf(const SimulationModel& model, const Placement& placement,
                     const MjcfOptions& options, const JointTrajectory* trajectory = nullptr);

}  // namespace graspsynth
