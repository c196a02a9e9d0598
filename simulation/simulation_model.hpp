#pragma once

/// @file
/// The immutable description of a simulated grasp scene (STYLE.md's Model/Data split): the
/// robot and the scene as loaded from models/, and the physics parameters of the ODE world.
/// Build it once and share it between threads; every thread makes its own SimulationData
/// (simulation/simulation_data.hpp) from it.
///
/// The physics model (reference/ode.md, measured again in this model; models/README.md,
/// "Physics"): ODE's direct solver dWorldStep, pyramid friction (dContactApprox1) with soft
/// contacts given as a spring-damper (kp, kd), implicit hinge motors for every joint.

#include <string>

#include "kinematics/robot_description.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// Physics parameters of the world. Defaults are the measured recipe of reference/ode.md.
struct SimulationOptions {
  double erp = 0.2;                  ///< world error reduction parameter (joints), 1
  double cfm = 1e-9;                 ///< world constraint force mixing (joints), > 0
  double contact_kp = 2e5;           ///< contact stiffness, N/m (soft ERP/CFM from kp, kd, h)
  double contact_kd = 500.0;         ///< contact damping, N s/m
  double surface_layer = 0.0005;     ///< allowed contact penetration, m
  double max_correcting_vel = 0.5;   ///< cap on contact correction velocity, m/s
  int max_contacts_per_pair = 4;     ///< contact points per geom pair, 1..16
  double gravity = 9.81;             ///< m/s^2, along -z of the world
  double finger_servo_gain = 20.0;   ///< position mode: joint velocity = gain * error, 1/s
  double arm_servo_gain = 20.0;      ///< position mode of the arm joints, 1/s
  double hand_table_friction = 0.8;  ///< Coulomb coefficient of finger-table contacts
  double arm_object_friction = 0.5;  ///< Coulomb coefficient of arm-object contacts
  /// Fingers (MCP/PIP/DIP flexion and ab/adduction) and thumb joints use the torque caps of
  /// the robot description (URDF efforts: 0.5 / 0.2 / 2.0 N m); arm joints those of
  /// reference/robot.md 1.4 (200, 200, 80, 80, 15, 15, 10 N m), also from the description.
  /// This factor scales every hand cap (1 = as described), for experiments.
  double hand_effort_scale = 1.0;

  /// True when every value is finite and in its range; otherwise false with the reason.
  bool IsValid(std::string* why) const;
};

/// Changes of the physics in one world relative to the model's (SimulationOptions and the
/// scene), for robustness evaluation (simulation/physics_perturbation.hpp draws them). Every
/// factor 1 and a zero offset leave the world exactly as modelled.
struct PhysicsVariation {
  double object_hand_friction = 1.0;   ///< factor on the object's coefficient with the hand
  double object_table_friction = 1.0;  ///< factor on the object-table coefficient
  double contact_stiffness = 1.0;      ///< factor on contact_kp (every contact)
  double contact_damping = 1.0;        ///< factor on contact_kd (every contact)
  double object_mass = 1.0;            ///< factor on the object's mass and inertia
  /// Shift of the object's centre of mass from the modelled one, object frame O, m (the
  /// inertia about the centre of mass is kept).
  Eigen::Vector3d object_com_offset = Eigen::Vector3d::Zero();
  double hand_effort = 1.0;  ///< factor on every finger servo's force (torque) cap

  /// True when every factor is finite and positive and the offset finite (and under 5 cm, so
  /// that the centre of mass stays inside the object); otherwise false with the reason.
  bool IsValid(std::string* why) const;
  /// True when the variation changes nothing.
  bool IsNominal() const;

  bool operator==(const PhysicsVariation&) const = default;
};

/// Robot + scene + physics parameters. Immutable once built.
class SimulationModel {
 public:
  /// Throws InputError when `options` is not valid (with IsValid's reason).
  SimulationModel(RobotModel robot, SceneModel scene, SimulationOptions options = {});

  const RobotModel& robot() const { return robot_; }
  const SceneModel& scene() const { return scene_; }
  const SimulationOptions& options() const { return options_; }
  /// The object's mass properties (ObjectModel::Inertia: its parts at uniform density).
  const ObjectInertia& object_inertia() const { return object_inertia_; }

 private:
  RobotModel robot_;
  SceneModel scene_;
  SimulationOptions options_;
  ObjectInertia object_inertia_;
};

/// Loads the shipped robot description and scene (DefaultRobotDescriptionPath,
/// DefaultSceneModelPath) into a model with `options`.
SimulationModel LoadDefaultSimulationModel(const SimulationOptions& options = {});

}  // namespace graspsynth
