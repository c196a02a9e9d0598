#pragma once

/// @file
/// What the judgement of a trial (simulation/trial_judge.hpp) reads of a simulated world after a
/// step, whatever engine stepped it: the time, the object's and the wrist's poses, what touched
/// what, the object-hand contacts with their forces, the controller's limit clamp, and the
/// figures of a numerical instability. The ODE world (SimulationData) and the MuJoCo world
/// (simulation_mujoco/mujoco_world.hpp) are both judged through it, by the same functions.

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace graspsynth {

/// What touched what in the last collision pass.
struct ContactReport {
  int total = 0;               ///< contact joints created
  int object_hand = 0;         ///< object with fingers or palm
  int object_table = 0;        ///< object with the table
  int object_arm = 0;          ///< object with arm links
  int finger_table = 0;        ///< fingers with the table
  int arm_table = 0;           ///< arm links, hand mount or palm with the table (not resolved)
  std::string arm_table_link;  ///< first link found touching the table
  /// Hand links touching the object: bit j for the child link of hand joint j
  /// (HandJointVector order), bit 20 for the palm or the hand mount.
  unsigned long hand_links_on_object = 0;
  double max_object_penetration = 0.0;  ///< deepest contact involving the object, m
};

/// One contact point between the object and a finger or the palm, as the last collision pass
/// made it (for grasp-quality evaluation).
struct HandObjectContact {
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();  ///< contact point, world, m
  Eigen::Vector3d n_W = Eigen::Vector3d::UnitZ();  ///< unit normal, world, pointing into the object
  double depth = 0.0;                              ///< penetration depth, m
  int hand_link = -1;  ///< HandJointVector index of the finger link, 20 for the palm or mount
  /// Force this contact put on the object in the step that followed the pass (world, N); zero
  /// after a detection-only pass (StepKinematically).
  Eigen::Vector3d f_W = Eigen::Vector3d::Zero();
  /// Coulomb coefficient of the object part touched, as modelled (before any PhysicsVariation).
  double friction = 1.0;
};

/// A world as the judgement sees it (see the file comment). Every accessor describes the state
/// after the last step (or the initial state before the first).
class JudgedWorld {
 public:
  virtual ~JudgedWorld() = default;

  /// Simulated time since the world was made, s.
  virtual double time() const = 0;
  /// Pose X_WO of the object frame.
  virtual Eigen::Isometry3d object_pose() const = 0;
  /// Linear velocity of the object's centre of mass (m/s) and its angular velocity (rad/s),
  /// world frame.
  virtual Eigen::Vector3d object_velocity() const = 0;
  virtual Eigen::Vector3d object_angular_velocity() const = 0;
  /// Pose X_WH of the hand-mount frame H.
  virtual Eigen::Isometry3d wrist_pose() const = 0;
  /// Contacts of the last collision pass.
  virtual const ContactReport& contacts() const = 0;
  /// The object-hand contact points of the last collision pass, with their forces.
  virtual const std::vector<HandObjectContact>& hand_object_contacts() const = 0;
  /// Index (0..6) of an arm joint whose command was clamped to its limit in the last step, or
  /// -1; the commanded value is in limit_violation_value().
  virtual int limit_violation() const = 0;
  virtual double limit_violation_value() const = 0;
  /// False when a body's position, orientation or velocity is NaN or infinite.
  virtual bool IsFinite() const = 0;
  /// Kinetic energy of the fingers and the object, J.
  virtual double HandObjectKineticEnergy() const = 0;
  /// Largest linear (m/s) and angular (rad/s) speed of a finger link or the object.
  virtual double MaxDynamicSpeed() const = 0;
  virtual double MaxDynamicAngularSpeed() const = 0;
};

}  // namespace graspsynth
