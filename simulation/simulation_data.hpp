#pragma once

/// @file
/// The mutable ODE world of one simulation (STYLE.md's Data): the PA-10 links, the Gifu Hand
/// III phalanges, the table and the object, with the robot's joint controller. One per thread;
/// ODE types stay inside the implementation (pimpl).
///
/// Bodies and joints (built from SimulationModel's robot description and scene):
/// - the arm links S1..W1 and a "wrist" body (W2_link with the hand-mount adapter and the
///   palm, which are rigidly fixed to it) either follow the controller kinematically
///   (ArmMode::kKinematic: kinematic bodies whose pose and velocity are set every step, so
///   contacts see their motion) or are dynamic bodies on hinge joints driven by motors
///   (ArmMode::kDynamic); the base link is static geometry;
/// - with a kinematic wrist, each finger's base hinge hangs from a kinematic mount of its own
///   that copies the wrist body's pose and velocity before every step, so that ODE solves a
///   finger that touches nothing as an island of its own, and the object only with the
///   fingers that touch it, instead of the whole hand as one system through the shared wrist
///   (WorldOptions::finger_mounts; the benchmark trial 1.5x faster, the states changed at
///   roundoff only);
/// - with every arm body kinematic, a step is ODE's problem (the same rows, right-hand sides
///   and integration as dWorldStep) solved by SolveConstraints, which eliminates each
///   finger's hinge rows before the pivoting solve of the motors, stops and contacts
///   (WorldOptions::structured_solver; the same states to roundoff, trials 2.2-5.6x faster); the
///   other arm modes step with dWorldStep;
/// - the finger links (20 for the Gifu) are dynamic bodies on hinge joints, driven by implicit
/// motors
///   (dParamVel, capped by dParamFMax = the joint's effort); each DIP's target is its PIP's
///   measured angle (the four DIP couplings);
/// - the object is one dynamic body (cylinder + bar handle); the table a static box.
///
/// The controller, per joint and step: position mode, v = clamp(v_ff + gain * (target - q),
/// -v_max, v_max); velocity mode, v = clamp(target, -v_max, v_max). Arm targets are first
/// clamped to the joint limits (the controller enforces the E2/W2 ranges beyond +-180 deg,
/// which an ODE hinge stop cannot); a clamped command is reported (limit_violation()).
///
/// Collisions: hand-hand and arm-arm and arm-hand pairs are never tested. Finger, palm and
/// arm geometry touching the object, the object touching the table and fingers touching the
/// table make contacts (pyramid friction, soft contacts); the arm or palm touching the table
/// is only reported (contacts()), since a trial ends there.

#include <array>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "simulation/judged_world.hpp"
#include "simulation/simulation_model.hpp"

namespace graspsynth {

/// An internal error that ODE reported (a failed assertion, e.g. on a non-finite state). The
/// world that raised it must not be stepped again. RunTrial turns it into a failed trial.
class OdeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How the arm moves.
enum class ArmMode {
  kKinematic,  ///< kinematic bodies follow the controller model (infinitely strong arm)
  kDynamic,    ///< dynamic links on motor-driven hinges, in the same solve as the hand
  /// S1..E1 (80-200 N m motors, which do not yield to a grasp) kinematic as in kKinematic; the
  /// wrist joints E2, W1 and W2 (10-15 N m, which do) dynamic as in kDynamic.
  kWristDynamic,
};

/// The first arm joint (0-based: E2) that ArmMode::kWristDynamic simulates dynamically.
inline constexpr int kFirstWristJoint = 4;

/// How a joint target is read.
enum class ServoMode {
  kPosition,  ///< target angle, rad (with an optional velocity feed-forward)
  kVelocity,  ///< target joint velocity, rad/s
};

/// Construction options of one world.
struct WorldOptions {
  double time_step = 0.002;  ///< s, one physics and control step
  ArmMode arm_mode = ArmMode::kKinematic;
  double theta = 0.0;  ///< object orientation, rad (SceneModel::ObjectPose)
  /// The object centre on the table, world, m; empty: the scene's object centre.
  std::optional<Eigen::Vector2d> object_xy;
  /// Changes of the physics for this world (friction, contact stiffness and damping, the
  /// object's mass and centre of mass, the finger servos' force caps).
  PhysicsVariation physics;
  /// With a kinematic wrist, hang each finger from a kinematic mount of its own (the file
  /// comment) instead of from the wrist body. The same physics, solved as smaller systems:
  /// the states differ at roundoff. False keeps the one shared wrist body, on which the
  /// shipped demonstration sets were simulated (the synthetic operator keeps it, so that they
  /// reproduce byte for byte).
  bool finger_mounts = true;
  /// With every arm body kinematic (ArmMode::kKinematic), step the world with
  /// SolveConstraints (simulation/constraint_solver.hpp) instead of ODE's dWorldStep: the same
  /// rows, right-hand sides and integration, each finger's joint rows eliminated before the
  /// pivoting solve of the motors, stops and contacts. Ignored in the other arm modes.
  bool structured_solver = true;
  /// Find the contacts with ODE's dSpaceCollide (every pair of geoms) instead of the broad
  /// phase's list of the pairs whose categories may touch: the same pairs in the same order,
  /// so the same trial bit for bit (the option is there to show it).
  bool ode_broad_phase = false;

  /// True when the values are finite and in range; otherwise false with the reason.
  bool IsValid(std::string* why) const;
};

/// Size of the world (the figures a benchmark reports).
struct WorldCounts {
  int bodies = 0;  ///< dynamic and kinematic bodies
  int joints = 0;  ///< hinge joints (contacts not counted)
  int geoms = 0;   ///< collision primitives, the table included
  int dynamic_bodies = 0;
};

/// Where the time of the steps went.
struct StepStatistics {
  long dynamic_steps = 0;    ///< Step() calls
  long kinematic_steps = 0;  ///< StepKinematically() calls
  double collision_s = 0.0;  ///< wall time in collision detection
  double solver_s = 0.0;     ///< wall time in dWorldStep
  double control_s = 0.0;    ///< wall time in the controller, kinematics and body placement
  int max_contacts = 0;      ///< most contact joints in one step
};

/// The constraint forces and velocities of one step (SimulationData::StepBothWays), world
/// frame.
struct StepForces {
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  /// Per finger hinge (HandJointVector order): the force (N) and torque (N m) of its rows on
  /// its child link, then on its parent link (zero when the parent is a kinematic body), as
  /// dJointFeedback's f1, t1, f2, t2 (a motor's push at its stop, an external torque, is not
  /// in them).
  std::vector<Eigen::Matrix<double, 12, 1>> hinges;
  /// Per contact of the step's collision pass, in its order: the force and torque of its rows
  /// on its first body (dJointFeedback's f1, t1; never a kinematic body).
  std::vector<Vector6d> contacts;
  /// Per moving body (the finger links in HandJointVector order, then the object): its linear
  /// (m/s) and angular (rad/s) velocity after the step.
  std::vector<Vector6d> velocities;
};

/// One step taken from the same state by the structured step and by dWorldStep.
struct StepComparison {
  StepForces structured;  ///< SolveConstraints' answer
  StepForces ode;         ///< dWorldStep's
  /// The structured solve's islands in this step: solved at the first guess of their rows'
  /// states, of those after amending it, and solved by pivoting (ConstraintSolverStatistics).
  long guessed = 0, amended = 0, pivoted = 0;
};

/// One ODE world. Not copyable; movable. Use from one thread at a time (each thread that uses
/// one must be a thread ODE knows about: the constructor registers the calling thread).
class SimulationData final : public JudgedWorld {
 public:
  /// Builds the world with the arm at `arm_q` (rad), the hand at `hand_f` (rad, DIPs equal to
  /// their PIPs), everything at rest, the object at rest on the table at options.theta, and
  /// position-mode commands holding that configuration. The model must outlive the data.
  /// Throws InputError when `options` is not valid.
  SimulationData(const SimulationModel& model, const WorldOptions& options, const Vector7d& arm_q,
                 const HandVector& hand_f);
  ~SimulationData() override;
  SimulationData(SimulationData&&) noexcept;
  SimulationData& operator=(SimulationData&&) noexcept;
  SimulationData(const SimulationData&) = delete;
  SimulationData& operator=(const SimulationData&) = delete;

  /// Arm command, held until changed: position mode reads `value` as target angles (rad) and
  /// `velocity_ff` as their rate (rad/s); velocity mode reads `value` as joint velocities.
  void SetArmCommand(ServoMode mode, const Vector7d& value,
                     const Vector7d& velocity_ff = Vector7d::Zero());
  /// Hand command for f0..f15, held until changed (position: rad; velocity: rad/s).
  void SetHandCommand(ServoMode mode, const HandVector& value);

  /// One step of the full physics: controller, collision (contacts), dWorldStep. Throws
  /// OdeError, without stepping, when the state is not finite, and when ODE reports an
  /// internal error during the step (the world must then be discarded).
  void Step();
  /// One step without dynamics, for free space: the controller model moves arm and fingers
  /// exactly as their servos would without load, bodies are placed at their poses (velocities
  /// set), collisions are detected and reported but not resolved; the object is not moved.
  /// Use only while nothing touches (see contacts()).
  void StepKinematically();
  /// Step() with the structured step (WorldOptions::structured_solver, ArmMode::kKinematic)
  /// checked against ODE's dWorldStep: after the controller and the collision pass, dWorldStep
  /// steps the world with feedback on every finger hinge and contact joint, the state is put
  /// back (quaternions normalised again: the same state to roundoff), and the structured step
  /// steps it as Step() does; the world goes on from there. For tests: slower than Step().
  /// Throws what Step() throws; aborts (GS_DEMAND) without the structured step.
  StepComparison StepBothWays();

  /// Simulated time since construction, s.
  double time() const override;
  /// Measured arm joint angles (rad; E2 and W2 unwrapped beyond +-pi).
  Vector7d arm_positions() const;
  /// Measured actuated hand joints f0..f15, rad.
  HandVector hand_positions() const;
  /// Measured values of every hand joint (HandJointVector order, the hand's joint count), rad.
  HandJointVector hand_joint_positions() const;
  /// Pose X_WO of the object frame (the pan body's centre).
  Eigen::Isometry3d object_pose() const override;
  /// Linear velocity of the object's centre of mass (m/s) and its angular velocity (rad/s),
  /// world frame.
  Eigen::Vector3d object_velocity() const override;
  Eigen::Vector3d object_angular_velocity() const override;
  /// Pose X_WH of the hand-mount frame H.
  Eigen::Isometry3d wrist_pose() const override;
  /// Pose X_WL of arm link i in 1..7 (7: the flange frame F).
  Eigen::Isometry3d arm_link_pose(int i) const;
  /// Pose X_WL of hand link j (HandJointVector index: the child link of that joint).
  Eigen::Isometry3d hand_link_pose(int j) const;
  /// Contacts of the last collision pass.
  const ContactReport& contacts() const override;
  /// The object-hand contact points of the last collision pass (emptied by every pass).
  const std::vector<HandObjectContact>& hand_object_contacts() const override;
  /// Index (0..6) of an arm joint whose command was clamped to its limit in the last step,
  /// or -1; the commanded value is in limit_violation_value().
  int limit_violation() const override;
  double limit_violation_value() const override;
  /// False when a body's position, orientation or velocity is NaN or infinite.
  bool IsFinite() const override;
  /// Kinetic energy of the fingers and the object (J): the part the solver can destabilize.
  double HandObjectKineticEnergy() const override;
  /// Largest linear (m/s) and angular (rad/s) speed of a finger link or the object.
  double MaxDynamicSpeed() const override;
  double MaxDynamicAngularSpeed() const override;

  WorldCounts counts() const;
  const StepStatistics& statistics() const;

  /// Sets the object's velocity (world frame). For tests and fault injection (e.g. a NaN to
  /// check that instability is detected).
  void SetObjectVelocity(const Eigen::Vector3d& v, const Eigen::Vector3d& w);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Makes the calling thread usable for ODE (dInitODE2 once per process,
/// dAllocateODEDataForThread once per thread; released when the thread ends). Called by
/// SimulationData's constructor; worker pools may call it up front.
void EnsureOdeThread();

}  // namespace graspsynth
