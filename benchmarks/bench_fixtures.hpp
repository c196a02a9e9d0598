#pragma once

/// @file
/// Inputs shared by the benchmark binaries: the shipped robot and a fixed, seeded set of
/// reachable flange targets made from random in-limit configurations.

#include <random>
#include <vector>

#include "common/data_dir.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"

namespace graspsynth::bench {

/// The shipped robot description, loaded once.
inline const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}

/// The KUKA LBR iiwa 14's arm from its shipped robot file, loaded once.
inline const ArmModel& IiwaArm() {
  static const ArmModel arm =
      LoadArmFromRobotFile(DataDirectory() / "models/iiwa14_allegro.robot.json");
  return arm;
}

/// A reachable flange target with the configuration that produced it.
struct ArmTarget {
  Vector7d q;              ///< in-limit configuration
  Eigen::Isometry3d X_WF;  ///< FK(q)
  double psi = 0.0;        ///< ArmAngleOf(q)
};

/// `count` targets of `arm` from uniformly random in-limit configurations (seeded, so every run
/// and every binary sees the same set). Configurations within 0.05 rad of the singular S2 = 0,
/// E1 = 0 or W1 = 0 are redrawn.
inline std::vector<ArmTarget> ReachableTargets(const ArmModel& arm, int count,
                                               uint64_t seed = 20261125) {
  std::mt19937_64 rng(seed);
  std::vector<ArmTarget> targets;
  while (static_cast<int>(targets.size()) < count) {
    ArmTarget t;
    for (int i = 0; i < kArmDof; ++i) {
      t.q[i] = std::uniform_real_distribution<double>(arm.lower()[i], arm.upper()[i])(rng);
    }
    if (std::abs(t.q[1]) < 0.05 || std::abs(t.q[3]) < 0.05 || std::abs(t.q[5]) < 0.05) continue;
    t.X_WF = ArmFlangePose(arm, t.q);
    t.psi = ArmAngleOf(arm, t.q);
    targets.push_back(t);
  }
  return targets;
}

/// ReachableTargets of the shipped robot's arm (the PA-10).
inline std::vector<ArmTarget> ReachableTargets(int count, uint64_t seed = 20261125) {
  return ReachableTargets(Robot().arm, count, seed);
}

}  // namespace graspsynth::bench
