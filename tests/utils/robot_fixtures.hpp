#pragma once

/// @file
/// Sample robots for tests: the PA-10-7C from its DH table and limits (reference/robot.md 1.3,
/// 1.4), independent of the URDF loader, and the path of the shipped robot description.

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "kinematics/arm_model.hpp"
#include "tests/utils/paths.hpp"

namespace graspsynth::testing {

inline double Deg(double degrees) { return degrees * M_PI / 180.0; }

inline Vector7d Pa10Upper() {
  Vector7d u;
  u << Deg(177), Deg(94), Deg(174), Deg(137), Deg(255), Deg(165), Deg(255);
  return u;
}
inline Vector7d Pa10Lower() { return -Pa10Upper(); }

/// The PA-10-7C kinematics with the limits of robot.md 1.4.
inline ArmModel Pa10FromDh() {
  Vector7d vel;
  vel << 1, 1, 2, 2, 2 * M_PI, 2 * M_PI, 2 * M_PI;
  Vector7d eff;
  eff << 200, 200, 80, 80, 15, 15, 10;
  return ArmModel::FromDh({0.317, 0.450, 0.480, 0.070}, Pa10Lower(), Pa10Upper(), vel, eff);
}

/// A configuration drawn uniformly within the arm's joint limits (rad).
inline Vector7d RandomConfiguration(const ArmModel& arm, std::mt19937_64* rng) {
  Vector7d q;
  for (int i = 0; i < kArmDof; ++i) {
    q[i] = std::uniform_real_distribution<double>(arm.lower()[i], arm.upper()[i])(*rng);
  }
  return q;
}

/// True when S2, E1 or W1 (DH values) is within 1e-3 rad of 0 or pi, where the IK is
/// numerically singular.
inline bool NearSingular(const Vector7d& q) {
  constexpr double kSingularMargin = 1e-3;
  return std::abs(std::sin(q[1])) < kSingularMargin || std::abs(std::sin(q[3])) < kSingularMargin ||
         std::abs(std::sin(q[5])) < kSingularMargin;
}

/// The larger of the position difference (m) and the largest rotation-matrix entry difference.
inline double PoseError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return std::max((a.translation() - b.translation()).norm(),
                  (a.linear() - b.linear()).cwiseAbs().maxCoeff());
}

/// The shipped robot description.
inline std::string ShippedUrdfPath() {
  return std::string(::testing::SourceDir()) + "/models/pa10_gifu3.urdf";
}

}  // namespace graspsynth::testing
