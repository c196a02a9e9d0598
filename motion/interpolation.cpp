#include "motion/interpolation.hpp"

#include "common/demand.hpp"
#include "common/valid_options.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth {

bool BlendOptions::IsValid(std::string* why) const {
  if (waypoints < 2) {
    if (why) *why = "BlendOptions::waypoints must be at least 2, is " + std::to_string(waypoints);
    return false;
  }
  return true;
}

double BlendParameter(double theta, double theta1, double theta2) {
  GS_DEMAND(theta1 != theta2, "blending two motions of the same orientation");
  return (theta - theta1) / (theta2 - theta1);
}

GraspingMotion BlendMotions(const GraspingMotion& m1, const GraspingMotion& m2, double t,
                            const BlendOptions& options) {
  RequireValid(options, "invalid BlendOptions");
  const GraspingMotion a = Resample(m1, options.waypoints, options.resample);
  const GraspingMotion b = Resample(m2, options.waypoints, options.resample);
  // exact endpoints: t = 0 and t = 1 reproduce the inputs bit for bit.
  if (t == 0.0) return a;
  if (t == 1.0) return b;

  GraspingMotion out;
  out.theta = (1.0 - t) * a.theta + t * b.theta;
  out.p_WO = (1.0 - t) * a.p_WO + t * b.p_WO;
  out.source = "blend(" + m1.source + ", " + m2.source + ", t=" + std::to_string(t) + ")";
  out.waypoints.resize(a.waypoints.size());
  for (size_t i = 0; i < a.waypoints.size(); ++i) {
    const MotionWaypoint& wa = a.waypoints[i];
    const MotionWaypoint& wb = b.waypoints[i];
    MotionWaypoint& w = out.waypoints[i];
    w.t = (1.0 - t) * wa.t + t * wb.t;
    w.p_WH = out.p_WO + Aslerp(wa.p_WH - a.p_WO, wb.p_WH - b.p_WO, t);
    w.q_WH = Slerp(wa.q_WH, wb.q_WH, t);
    w.f = ConvexBlend(wa.f, wb.f, t);
  }
  return out;
}

GraspingMotion BlendMotionsWeighted(const std::vector<const GraspingMotion*>& motions,
                                    const std::vector<double>& weights,
                                    const BlendOptions& options) {
  RequireValid(options, "invalid BlendOptions");
  GS_DEMAND(!motions.empty() && motions.size() == weights.size(), "one weight per motion");
  std::vector<GraspingMotion> m;
  for (const GraspingMotion* motion : motions) {
    m.push_back(Resample(*motion, options.waypoints, options.resample));
  }
  for (size_t i = 0; i < m.size(); ++i) {
    if (weights[i] == 1.0) return m[i];  // exact at a vertex
  }
  GraspingMotion out;
  out.source = "blend(";
  for (size_t i = 0; i < m.size(); ++i) {
    out.theta += weights[i] * m[i].theta;
    out.p_WO += weights[i] * m[i].p_WO;
    out.source +=
        motions[i]->source + " w=" + std::to_string(weights[i]) + (i + 1 < m.size() ? ", " : ")");
  }
  const size_t n = m.front().waypoints.size();
  out.waypoints.resize(n);
  std::vector<Eigen::Vector3d> p(m.size());
  std::vector<Eigen::Quaterniond> q(m.size());
  for (size_t k = 0; k < n; ++k) {
    MotionWaypoint& w = out.waypoints[k];
    w.f.setZero();
    for (size_t i = 0; i < m.size(); ++i) {
      const MotionWaypoint& wi = m[i].waypoints[k];
      w.t += weights[i] * wi.t;
      w.f += weights[i] * wi.f;
      p[i] = wi.p_WH - m[i].p_WO;
      q[i] = wi.q_WH;
    }
    w.p_WH = out.p_WO + WeightedAslerp(p, weights);
    w.q_WH = WeightedSlerp(q, weights);
  }
  out.waypoints.front().t = 0.0;
  return out;
}

}  // namespace graspsynth
