#include "motion/resample.hpp"

#include <algorithm>

#include "common/demand.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth {
namespace {

// Blend of waypoints a and b at fraction u in [0, 1].
MotionWaypoint Between(const MotionWaypoint& a, const MotionWaypoint& b, double u) {
  MotionWaypoint w;
  w.t = (1.0 - u) * a.t + u * b.t;
  w.p_WH = (1.0 - u) * a.p_WH + u * b.p_WH;
  w.q_WH = Slerp(a.q_WH, b.q_WH, u);
  w.f = ConvexBlend(a.f, b.f, u);
  return w;
}

// The motion at parameter value s, where param[i] is the (non-decreasing) parameter of
// waypoint i.
MotionWaypoint SampleAtParameter(const GraspingMotion& motion, const std::vector<double>& param,
                                 double s) {
  const auto& w = motion.waypoints;
  if (s <= param.front()) return w.front();
  if (s >= param.back()) return w.back();
  // first waypoint with parameter > s; its predecessor has parameter <= s.
  const size_t hi =
      static_cast<size_t>(std::upper_bound(param.begin(), param.end(), s) - param.begin());
  const size_t lo = hi - 1;
  const double span = param[hi] - param[lo];
  const double u = span > 0.0 ? (s - param[lo]) / span : 0.0;
  return Between(w[lo], w[hi], u);
}

}  // namespace

MotionWaypoint SampleAt(const GraspingMotion& motion, double t) {
  GS_DEMAND(!motion.waypoints.empty(), "sampling an empty grasping motion");
  std::vector<double> times(motion.waypoints.size());
  for (size_t i = 0; i < times.size(); ++i) times[i] = motion.waypoints[i].t;
  return SampleAtParameter(motion, times, t);
}

GraspingMotion Resample(const GraspingMotion& motion, int count, ResampleMode mode) {
  GS_DEMAND(count >= 2, "resampling needs at least 2 waypoints");
  GS_DEMAND(IsWellFormed(motion, nullptr), "resampling a malformed grasping motion");
  const auto& w = motion.waypoints;
  std::vector<double> param(w.size(), 0.0);
  for (size_t i = 1; i < w.size(); ++i) {
    param[i] = param[i - 1] + (mode == ResampleMode::kArcLength ? (w[i].p_WH - w[i - 1].p_WH).norm()
                                                                : w[i].t - w[i - 1].t);
  }
  if (param.back() <= 0.0) {
    // a wrist that never moves has no arc length to spread over: use time.
    for (size_t i = 0; i < w.size(); ++i) param[i] = w[i].t;
  }
  GraspingMotion out = motion;
  out.waypoints.resize(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) {
    const double s = param.back() * static_cast<double>(k) / static_cast<double>(count - 1);
    out.waypoints[static_cast<size_t>(k)] = SampleAtParameter(motion, param, s);
  }
  out.waypoints.front() = w.front();
  out.waypoints.back() = w.back();
  return out;
}

}  // namespace graspsynth
