#include "motion/reach.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "common/demand.hpp"
#include "common/valid_options.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth {
namespace {

bool Fail(std::string* why, const std::string& text) {
  if (why) *why = text;
  return false;
}

// Number of samples that cover `duration` at `period`, the last one landing on the end.
int SampleCount(double duration, double period) {
  return std::max(1, static_cast<int>(std::ceil(duration / period - 1e-9)));
}

double SmoothStep(double u) { return u * u * (3.0 - 2.0 * u); }

// Clamped cubic spline through knots (times T, points P) with end velocities v0, vm:
// the second derivatives M solve the tridiagonal system of the clamped end conditions.
class ClampedSpline {
 public:
  ClampedSpline(std::vector<double> T, std::vector<Eigen::Vector3d> P, const Eigen::Vector3d& v0,
                const Eigen::Vector3d& vm)
      : T_(std::move(T)), P_(std::move(P)), M_(P_.size()) {
    const int n = static_cast<int>(P_.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, 3);
    for (int i = 0; i < n; ++i) {
      if (i == 0) {
        const double h = T_[1] - T_[0];
        A(0, 0) = 2 * h;
        A(0, 1) = h;
        b.row(0) = 6 * ((P_[1] - P_[0]) / h - v0).transpose();
      } else if (i == n - 1) {
        const double h = T_[i] - T_[i - 1];
        A(i, i - 1) = h;
        A(i, i) = 2 * h;
        b.row(i) = 6 * (vm - (P_[i] - P_[i - 1]) / h).transpose();
      } else {
        const double h0 = T_[i] - T_[i - 1];
        const double h1 = T_[i + 1] - T_[i];
        A(i, i - 1) = h0;
        A(i, i) = 2 * (h0 + h1);
        A(i, i + 1) = h1;
        b.row(i) = 6 * ((P_[i + 1] - P_[i]) / h1 - (P_[i] - P_[i - 1]) / h0).transpose();
      }
    }
    const Eigen::MatrixXd M = A.partialPivLu().solve(b);
    for (int i = 0; i < n; ++i) M_[i] = M.row(i).transpose();
  }

  Eigen::Vector3d operator()(double t) const {
    size_t i = 0;
    while (i + 2 < T_.size() && t > T_[i + 1]) ++i;
    const double h = T_[i + 1] - T_[i];
    const double a = T_[i + 1] - t;
    const double c = t - T_[i];
    return M_[i] * (a * a * a) / (6 * h) + M_[i + 1] * (c * c * c) / (6 * h) +
           (P_[i] / h - M_[i] * h / 6) * a + (P_[i + 1] / h - M_[i + 1] * h / 6) * c;
  }

 private:
  std::vector<double> T_;
  std::vector<Eigen::Vector3d> P_;
  std::vector<Eigen::Vector3d> M_;
};

// Orientation and fingers from start to end at progress s in [0, 1].
MotionWaypoint Progress(const MotionWaypoint& start, const MotionWaypoint& end, double s) {
  MotionWaypoint w;
  w.q_WH = Slerp(start.q_WH, end.q_WH, s);
  w.f = ConvexBlend(start.f, end.f, s);
  return w;
}

}  // namespace

bool SplineReachOptions::IsValid(std::string* why) const {
  if (!(duration > 0.0)) return Fail(why, "SplineReachOptions::duration must be positive");
  if (!(sample_period > 0.0 && sample_period <= duration)) {
    return Fail(why, "SplineReachOptions::sample_period must be in (0, duration]");
  }
  for (const Eigen::Vector3d& v : via_points) {
    if (!v.allFinite()) return Fail(why, "SplineReachOptions::via_points must be finite");
  }
  return true;
}

CartesianPath SplineReach(const MotionWaypoint& start, const MotionWaypoint& pregrasp,
                          const Eigen::Vector3d& v_end, const SplineReachOptions& options) {
  RequireValid(options, "invalid SplineReachOptions");
  std::vector<Eigen::Vector3d> points = {start.p_WH};
  points.insert(points.end(), options.via_points.begin(), options.via_points.end());
  points.push_back(pregrasp.p_WH);
  // knot times in proportion to chord length (uniform when the wrist does not move).
  std::vector<double> chord(points.size(), 0.0);
  for (size_t i = 1; i < points.size(); ++i) {
    chord[i] = chord[i - 1] + std::max((points[i] - points[i - 1]).norm(), 1e-9);
  }
  std::vector<double> knots(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    knots[i] = options.duration * chord[i] / chord.back();
  }
  const ClampedSpline spline(knots, points, Eigen::Vector3d::Zero(), v_end);

  const int n = SampleCount(options.duration, options.sample_period);
  CartesianPath path;
  path.reserve(static_cast<size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) {
    const double tau = std::min(k * options.sample_period, options.duration);
    MotionWaypoint w = Progress(start, pregrasp, SmoothStep(tau / options.duration));
    w.t = start.t + tau;
    w.p_WH = spline(tau);
    path.push_back(w);
  }
  path.back().p_WH = pregrasp.p_WH;
  path.back().q_WH = pregrasp.q_WH;
  path.back().f = pregrasp.f;
  return path;
}

bool DmpReachOptions::IsValid(std::string* why) const {
  if (!(duration > 0.0)) return Fail(why, "DmpReachOptions::duration must be positive");
  if (!(sample_period > 0.0 && sample_period <= duration)) {
    return Fail(why, "DmpReachOptions::sample_period must be in (0, duration]");
  }
  if (basis_functions < 2) return Fail(why, "DmpReachOptions::basis_functions must be >= 2");
  if (!(alpha_z > 0.0 && alpha_x > 0.0)) {
    return Fail(why, "DmpReachOptions::alpha_z and alpha_x must be positive");
  }
  if (!(integration_step > 0.0 && integration_step <= sample_period)) {
    return Fail(why, "DmpReachOptions::integration_step must be in (0, sample_period]");
  }
  return true;
}

PositionDmp::PositionDmp(const std::vector<double>& times,
                         const std::vector<Eigen::Vector3d>& positions,
                         const DmpReachOptions& options)
    : options_(options) {
  RequireValid(options, "invalid DmpReachOptions");
  GS_DEMAND(times.size() == positions.size() && times.size() >= 3,
            "a DMP needs at least 3 demonstrated samples");
  const int nb = options.basis_functions;
  // kernels evenly spaced in time, i.e. exponentially in the phase x = exp(-alpha_x t / tau).
  centres_.resize(nb);
  widths_.resize(nb);
  for (int i = 0; i < nb; ++i) {
    centres_[i] = std::exp(-options.alpha_x * static_cast<double>(i) / (nb - 1));
  }
  for (int i = 0; i < nb; ++i) {
    const double gap = i + 1 < nb ? centres_[i] - centres_[i + 1] : centres_[i - 1] - centres_[i];
    widths_[i] = 1.0 / (gap * gap);
  }

  const size_t n = times.size();
  const double tau = times.back() - times.front();
  GS_DEMAND(tau > 0.0, "a DMP demonstration needs a positive duration");
  const Eigen::Vector3d g = positions.back();
  const double az = options.alpha_z;
  const double bz = az / 4.0;
  // velocities and accelerations by finite differences on the (possibly uneven) samples.
  std::vector<Eigen::Vector3d> vel(n), acc(n);
  for (size_t i = 0; i < n; ++i) {
    const size_t a = i == 0 ? 0 : i - 1;
    const size_t b = i + 1 == n ? n - 1 : i + 1;
    vel[i] = (positions[b] - positions[a]) / (times[b] - times[a]);
  }
  for (size_t i = 0; i < n; ++i) {
    const size_t a = i == 0 ? 0 : i - 1;
    const size_t b = i + 1 == n ? n - 1 : i + 1;
    acc[i] = (vel[b] - vel[a]) / (times[b] - times[a]);
  }
  // locally weighted regression of f_target = tau^2 a - alpha_z (beta_z (g - y) - tau v)
  // on the regressor s = x.
  weights_ = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(nb, 3);
  Eigen::VectorXd sxx = Eigen::VectorXd::Zero(nb);
  Eigen::Matrix<double, Eigen::Dynamic, 3> sxf =
      Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(nb, 3);
  for (size_t k = 0; k < n; ++k) {
    const double x = std::exp(-options.alpha_x * (times[k] - times.front()) / tau);
    const Eigen::Vector3d f = tau * tau * acc[k] - az * (bz * (g - positions[k]) - tau * vel[k]);
    for (int i = 0; i < nb; ++i) {
      const double psi = std::exp(-widths_[i] * (x - centres_[i]) * (x - centres_[i]));
      sxx[i] += psi * x * x;
      sxf.row(i) += psi * x * f.transpose();
    }
  }
  for (int i = 0; i < nb; ++i) {
    if (sxx[i] > 1e-12) weights_.row(i) = sxf.row(i) / sxx[i];
  }
}

Eigen::Vector3d PositionDmp::Forcing(double x) const {
  Eigen::Vector3d num = Eigen::Vector3d::Zero();
  double den = 1e-12;
  for (int i = 0; i < centres_.size(); ++i) {
    const double psi = std::exp(-widths_[i] * (x - centres_[i]) * (x - centres_[i]));
    num += psi * weights_.row(i).transpose();
    den += psi;
  }
  return num / den * x;
}

std::vector<Eigen::Vector3d> PositionDmp::Rollout(const Eigen::Vector3d& y0,
                                                  const Eigen::Vector3d& g) const {
  const double tau = options_.duration;
  const double az = options_.alpha_z;
  const double bz = az / 4.0;
  const double h = options_.integration_step;
  const int n = SampleCount(tau, options_.sample_period);
  std::vector<Eigen::Vector3d> out;
  out.reserve(static_cast<size_t>(n) + 1);
  Eigen::Vector3d y = y0;
  Eigen::Vector3d z = Eigen::Vector3d::Zero();
  double x = 1.0;
  double t = 0.0;
  out.push_back(y);
  for (int k = 1; k <= n; ++k) {
    const double t_next = std::min(k * options_.sample_period, tau);
    while (t < t_next - 1e-12) {
      const double dt = std::min(h, t_next - t);
      const Eigen::Vector3d zd = (az * (bz * (g - y) - z) + Forcing(x)) / tau;
      y += dt * z / tau;
      z += dt * zd;
      x += dt * (-options_.alpha_x * x / tau);
      t += dt;
    }
    out.push_back(y);
  }
  return out;
}

CartesianPath DmpReach(const PositionDmp& dmp, const MotionWaypoint& start,
                       const MotionWaypoint& pregrasp, const DmpReachOptions& options) {
  RequireValid(options, "invalid DmpReachOptions");
  const std::vector<Eigen::Vector3d> positions = dmp.Rollout(start.p_WH, pregrasp.p_WH);
  const double total = (pregrasp.p_WH - start.p_WH).norm();
  CartesianPath path;
  path.reserve(positions.size());
  for (size_t k = 0; k < positions.size(); ++k) {
    const double tau = std::min(static_cast<double>(k) * options.sample_period, options.duration);
    // progress along the straight start-goal line; the time profile when the wrist stays put.
    double s = total > 1e-9
                   ? (positions[k] - start.p_WH).dot(pregrasp.p_WH - start.p_WH) / (total * total)
                   : SmoothStep(tau / options.duration);
    s = std::clamp(s, 0.0, 1.0);
    MotionWaypoint w = Progress(start, pregrasp, s);
    w.t = start.t + tau;
    w.p_WH = positions[k];
    path.push_back(w);
  }
  path.back().p_WH = pregrasp.p_WH;
  path.back().q_WH = pregrasp.q_WH;
  path.back().f = pregrasp.f;
  return path;
}

double MinimumJerk(double u) {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
}

bool LiftOptions::IsValid(std::string* why) const {
  if (!(settle >= 0.0 && duration > 0.0 && hold >= 0.0)) {
    return Fail(why, "LiftOptions: settle and hold must be >= 0 and duration > 0");
  }
  if (!(height >= 0.0)) return Fail(why, "LiftOptions::height must be >= 0");
  if (!(sample_period > 0.0)) return Fail(why, "LiftOptions::sample_period must be positive");
  return true;
}

CartesianPath LiftPath(const MotionWaypoint& grasp, const LiftOptions& options) {
  RequireValid(options, "invalid LiftOptions");
  const double total = options.settle + options.duration + options.hold;
  const int n = SampleCount(total, options.sample_period);
  CartesianPath path;
  path.reserve(static_cast<size_t>(n));
  for (int k = 1; k <= n; ++k) {
    const double tau = std::min(k * options.sample_period, total);
    const double u = std::clamp((tau - options.settle) / options.duration, 0.0, 1.0);
    MotionWaypoint w = grasp;
    w.t = grasp.t + tau;
    w.p_WH.z() += options.height * MinimumJerk(u);
    path.push_back(w);
  }
  return path;
}

}  // namespace graspsynth
