#include "scene/rest_pose.hpp"

#include <cmath>
#include <cstdio>
#include <optional>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"

namespace graspsynth {
Vector7d DefaultRestConfiguration(const RobotModel& robot, const SceneModel& scene,
                                  const Eigen::Matrix3d& R_WH) {
  const Eigen::Vector2d toward = scene.object_centre_xy.normalized();
  const Eigen::Matrix3d R = R_WH * Eigen::AngleAxisd(30.0 * kDeg, Eigen::Vector3d::UnitY());
  const Eigen::Vector3d p(0.60 * toward.x(), 0.60 * toward.y(), scene.table.top_z + 0.30);
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = R;
  X_WH.translation() = p;
  const Eigen::Isometry3d X_WF = X_WH * robot.X_FH.inverse();
  const std::optional<MidArcSolution> s = SolveArmIkMidArc(robot.arm, X_WF, ArmBranch{});
  if (!s) {
    char where[160];
    std::snprintf(where, sizeof(where), "(%.3f, %.3f, %.3f) m", p.x(), p.y(), p.z());
    throw InputError("scene " + scene.source +
                     ": the arm's rest pose is out of reach on the elbow-up branch (the wrist " +
                     where +
                     ", 0.60 m from the base toward the object centre and 0.30 m above the "
                     "table top at table.top_z)");
  }
  return s->q;
}

}  // namespace graspsynth
