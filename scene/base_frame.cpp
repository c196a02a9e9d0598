#include "scene/base_frame.hpp"

#include <algorithm>
#include <cmath>

#include "common/errors.hpp"
#include "common/format.hpp"

namespace graspsynth {
namespace {

// the largest tilt or turn between two frames that still counts as none, rad.
constexpr double kTurnTolerance = 1e-9;

}  // namespace

SceneModel SceneInBaseFrame(SceneModel scene, const Eigen::Isometry3d& X_WB) {
  if (scene.X_WS.matrix() == X_WB.matrix()) return scene;
  // X_BS: the scene's current frame S seen from B.
  const Eigen::Isometry3d X_BS = X_WB.inverse() * scene.X_WS;
  const Eigen::Matrix3d& R = X_BS.linear();
  const double tilt = std::acos(std::clamp(R(2, 2), -1.0, 1.0));
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  if (tilt > kTurnTolerance || std::abs(yaw) > kTurnTolerance) {
    throw InputError(Format(
        "scene %s: the robot's base is tilted %.6g deg and turned %.6g deg about the vertical "
        "against the scene's frame; only a base shifted without a turn is supported yet (the "
        "table is an axis-aligned box)",
        scene.source.c_str(), tilt / kDeg, -yaw / kDeg));
  }
  const Eigen::Vector3d& p = X_BS.translation();
  scene.table.top_z += p.z();
  scene.table.centre_xy += p.head<2>();
  scene.object_centre_xy += p.head<2>();
  scene.X_WS = X_WB;
  return scene;
}

Eigen::Vector2d TablePointInScene(const SceneModel& scene, const Eigen::Vector2d& xy_W) {
  if (scene.X_WS.matrix() == Eigen::Isometry3d::Identity().matrix()) return xy_W;
  const Eigen::Vector3d p = scene.X_WS.inverse() * Eigen::Vector3d(xy_W.x(), xy_W.y(), 0.0);
  return p.head<2>();
}

}  // namespace graspsynth
