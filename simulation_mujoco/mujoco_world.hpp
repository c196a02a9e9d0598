#pragma once

/// @file
/// The mutable MuJoCo world of one trial (STYLE.md's Data): the exported MJCF model
/// (simulation_mujoco/mjcf_export.hpp) compiled by MuJoCo, its state, and the robot's joint
/// controller, judged as the ODE world is (simulation/judged_world.hpp). MuJoCo's types stay
/// inside the implementation (pimpl). One per thread.
///
/// The controller is the ODE world's (simulation/simulation_data.hpp), per joint and step:
/// position mode, v = clamp(v_ff + gain * (target - q), -v_max, v_max), arm targets clamped to
/// the joint limits first (reported by limit_violation()), a joint at its limit stopped, each
/// DIP's target its PIP's measured angle; v becomes the servo's control ctrl = q + v / gain
/// (mjcf_export.hpp: the servo's force is then kv (v - qdot) within its cap).
///
/// Available only when graspsynth is built with MuJoCo (MujocoAvailable()); otherwise making
/// a world throws InputError.

#include <memory>
#include <string>
#include <vector>

#include "simulation/judged_world.hpp"
#include "simulation/simulation_data.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation_mujoco/mjcf_export.hpp"

namespace graspsynth {

/// True when this build has the MuJoCo library (GRASPSYNTH_MUJOCO).
bool MujocoAvailable();

/// The MuJoCo version this build runs (e.g. "2.2.2"), or "none".
std::string MujocoVersion();

/// A MuJoCo model compiled from MJCF text, with its MjcfGeom roles. Immutable once made; share
/// it between the worlds of one thread or of several.
class MujocoModel {
 public:
  /// Compiles `mjcf` (its geoms' roles in `mjcf.geoms`) for `model`'s robot, which the world's
  /// controller reads (limits, gains). Throws InputError with MuJoCo's message when MuJoCo
  /// rejects the text, or when this build has no MuJoCo.
  MujocoModel(const SimulationModel& model, const MjcfModel& mjcf);
  ~MujocoModel();
  MujocoModel(const MujocoModel&) = delete;
  MujocoModel& operator=(const MujocoModel&) = delete;

  struct Impl;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// One MuJoCo world (see the file comment). Not copyable.
class MujocoData final : public JudgedWorld {
 public:
  /// The world at rest with the arm at `arm_q` (rad), the hand at `hand_f` (rad; the DIPs at
  /// their couplings) and the object where the MJCF put it, with position commands that hold
  /// that configuration. The model must outlive the data.
  MujocoData(const MujocoModel& model, const Vector7d& arm_q, const HandVector& hand_f);
  ~MujocoData() override;
  MujocoData(const MujocoData&) = delete;
  MujocoData& operator=(const MujocoData&) = delete;

  /// Position command of the arm (rad) with its rate (rad/s) as feed-forward, held until changed.
  void SetArmCommand(const Vector7d& target, const Vector7d& velocity_ff = Vector7d::Zero());
  /// Position command of f0..f15 (rad), held until changed.
  void SetHandCommand(const HandVector& target);
  /// One step: the controller, mj_step, then the contact report of the new state.
  void Step();
  /// Forward kinematics of the current joint positions (mj_kinematics), without stepping.
  void Kinematics();
  /// Sets the robot's joints (rad; the DIPs at their couplings) at rest, for tests.
  void SetRobotPositions(const Vector7d& arm_q, const HandVector& hand_f);

  double time() const override;
  Vector7d arm_positions() const;
  HandVector hand_positions() const;
  Eigen::Isometry3d object_pose() const override;
  Eigen::Vector3d object_velocity() const override;
  Eigen::Vector3d object_angular_velocity() const override;
  Eigen::Isometry3d wrist_pose() const override;
  /// Pose X_WL of arm link i in 1..7 (7: the flange frame F), as MuJoCo computed it.
  Eigen::Isometry3d arm_link_pose(int i) const;
  const ContactReport& contacts() const override;
  const std::vector<HandObjectContact>& hand_object_contacts() const override;
  int limit_violation() const override;
  double limit_violation_value() const override;
  bool IsFinite() const override;
  double HandObjectKineticEnergy() const override;
  double MaxDynamicSpeed() const override;
  double MaxDynamicAngularSpeed() const override;
  /// The bodies, joints and geoms of the model; steps taken (dynamic_steps) and their time.
  WorldCounts counts() const;
  const StepStatistics& statistics() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace graspsynth
