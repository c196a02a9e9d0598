#pragma once

/// @file
/// Small grasping motions for tests.

#include <cmath>

#include "motion/grasping_motion.hpp"

namespace graspsynth::testing {

/// A motion of `count` waypoints over `duration` s: the wrist moves on a straight line from
/// `from` to `to` (world, m) with a smooth (cosine) velocity profile, turns by `turn` rad about
/// z and the fingers close from 0 to `closure` rad; object centre at p_WO.
inline GraspingMotion LineMotion(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                 double turn, double closure, int count, double duration,
                                 const Eigen::Vector3d& p_WO = Eigen::Vector3d::Zero(),
                                 double theta = 0.0) {
  GraspingMotion m;
  m.theta = theta;
  m.p_WO = p_WO;
  m.source = "line";
  for (int i = 0; i < count; ++i) {
    const double u = static_cast<double>(i) / (count - 1);
    const double s = 0.5 - 0.5 * std::cos(M_PI * u);
    MotionWaypoint w;
    w.t = u * duration;
    w.p_WH = (1.0 - s) * from + s * to;
    w.q_WH = Eigen::Quaterniond(Eigen::AngleAxisd(s * turn, Eigen::Vector3d::UnitZ()));
    w.f = HandVector::Constant(s * closure);
    m.waypoints.push_back(w);
  }
  return m;
}

}  // namespace graspsynth::testing
