#include "kinematics/arm_reach.hpp"

#include <cmath>

namespace graspsynth {

Eigen::Vector3d ShoulderToWrist(const SrsLengths& lengths, const Eigen::Isometry3d& X_WF) {
  Eigen::Vector3d x_sw = X_WF.translation() - lengths.d_wt * X_WF.linear().col(2);
  x_sw.z() -= lengths.d_bs;
  return x_sw;
}

ArmReach ReachOfTarget(const ArmModel& arm, const Eigen::Isometry3d& X_WF) {
  const SrsLengths& len = arm.lengths();
  return {ShoulderToWrist(len, arm.dh_map().FlangeToDh(X_WF)).norm(), std::abs(len.d_se - len.d_ew),
          len.d_se + len.d_ew};
}

}  // namespace graspsynth
