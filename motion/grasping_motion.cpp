#include "motion/grasping_motion.hpp"
#include "kinematics/pose_math.hpp"

#include <cmath>

namespace graspsynth {

Eigen::Isometry3d WaypointPose(const MotionWaypoint& w) {
  Eigen::Isometry3d X = PoseFrom(w.p_WH, w.q_WH);
  return X;
}

bool IsWellFormed(const GraspingMotion& motion, std::string* why) {
  const auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (motion.waypoints.size() < 2) return fail("a grasping motion needs at least 2 waypoints");
  if (motion.waypoints.front().t != 0.0) return fail("the first waypoint is not at t = 0");
  if (!std::isfinite(motion.theta) || !motion.p_WO.allFinite()) {
    return fail("theta or the object centre is not finite");
  }
  for (size_t i = 0; i < motion.waypoints.size(); ++i) {
    const MotionWaypoint& w = motion.waypoints[i];
    const std::string where = "waypoint " + std::to_string(i) + ": ";
    if (!std::isfinite(w.t) || !w.p_WH.allFinite() || !w.q_WH.coeffs().allFinite() ||
        !w.f.allFinite()) {
      return fail(where + "a value is not finite");
    }
    if (i > 0 && !(w.t > motion.waypoints[i - 1].t)) return fail(where + "time does not increase");
    if (std::abs(w.q_WH.norm() - 1.0) > 1e-9) return fail(where + "quaternion is not unit");
  }
  return true;
}

}  // namespace graspsynth
