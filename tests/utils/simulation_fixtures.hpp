#pragma once

/// @file
/// Shared inputs of the simulation tests: the shipped model, the shipped 60 deg example
/// trajectory and trajectories derived from it that must fail.

#include <string>

#include "motion/joint_space.hpp"
#include "motion/joint_trajectory.hpp"
#include "motion/scripted_grasp.hpp"
#include "simulation/simulation_model.hpp"
#include "tests/utils/paths.hpp"

namespace graspsynth::testing {

/// The shipped robot and scene with the default physics.
inline const SimulationModel& ShippedSimulationModel() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

inline std::string ExamplePath() {
  return std::string(::testing::SourceDir()) + "/examples/grasp_60deg.json";
}

/// examples/grasp_60deg.json, loaded and limit-checked.
inline const JointTrajectory& ExampleTrajectory() {
  static const JointTrajectory t = LoadJointTrajectory(
      ExamplePath(), ShippedSimulationModel().robot().arm, ShippedSimulationModel().robot().hand);
  return t;
}

/// The example with the hand kept as it starts (open) throughout.
inline JointTrajectory HandKeptOpen() {
  JointTrajectory t = ExampleTrajectory();
  for (TrajectorySample& s : t.samples) s.hand = t.samples.front().hand;
  return t;
}

/// Fingers pointing down, the wrist lowered from 0.35 m to 0.05 m below the table top over
/// 2 s, beside the object: the hand is driven through the table.
inline JointTrajectory HandThroughTable() {
  const RobotModel& robot = ShippedSimulationModel().robot();
  Eigen::Matrix3d R;
  R.col(2) = -Eigen::Vector3d::UnitZ();
  R.col(0) = Eigen::Vector3d(0.28, -0.96, 0.0).normalized();
  R.col(1) = R.col(2).cross(R.col(0));
  CartesianPath path;
  for (int k = 0; k <= 100; ++k) {
    MotionWaypoint w;
    w.t = 0.02 * k;
    w.p_WH = Eigen::Vector3d(0.0, 0.55, 0.35 - 0.40 * k / 100.0);
    w.q_WH = Eigen::Quaterniond(R);
    w.f = RobotGraspOf(robot).open;
    path.push_back(w);
  }
  Eigen::Isometry3d X0 = Eigen::Isometry3d::Identity();
  X0.linear() = R;
  X0.translation() = path.front().p_WH;
  const std::optional<Vector7d> q0 = SolveWristPose(robot, X0, ArmBranch{}, 0.0, Vector7d::Zero());
  JointTrajectory trajectory = ToJointTrajectory(robot, path, q0.value()).trajectory;
  trajectory.theta_deg = 60.0;
  return trajectory;
}

/// Fewer cases under the sanitizers (GRASPSYNTH_SANITIZED): they slow our code down.
inline int Scaled(int full, int sanitized) {
#ifdef GRASPSYNTH_SANITIZED
  (void)full;
  return sanitized;
#else
  (void)sanitized;
  return full;
#endif
}

}  // namespace graspsynth::testing
