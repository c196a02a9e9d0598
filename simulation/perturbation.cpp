#include "simulation/perturbation.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/errors.hpp"
#include "common/valid_options.hpp"
#include "kinematics/arm_ik.hpp"
#include "motion/joint_space.hpp"
#include "simulation/random.hpp"

namespace graspsynth {
namespace {

struct KnotNoise {
  double t = 0.0;
  Eigen::Vector3d dp = Eigen::Vector3d::Zero();
  Eigen::Vector3d dr = Eigen::Vector3d::Zero();
  HandVector df = HandVector::Zero();
};

// Offsets at time t: smooth-step blend of the bracketing knots.
KnotNoise NoiseAt(const std::vector<KnotNoise>& knots, double t) {
  if (t <= knots.front().t) return knots.front();
  if (t >= knots.back().t) return knots.back();
  const auto next = std::upper_bound(knots.begin(), knots.end(), t,
                                     [](double time, const KnotNoise& k) { return time < k.t; });
  const KnotNoise& a = *(next - 1);
  const KnotNoise& b = *next;
  const double u = (t - a.t) / (b.t - a.t);
  const double s = u * u * (3.0 - 2.0 * u);
  KnotNoise out;
  out.t = t;
  out.dp = (1.0 - s) * a.dp + s * b.dp;
  out.dr = (1.0 - s) * a.dr + s * b.dr;
  out.df = (1.0 - s) * a.df + s * b.df;
  return out;
}

Eigen::Matrix3d ExpRotation(const Eigen::Vector3d& r) {
  const double angle = r.norm();
  if (angle < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, r / angle).toRotationMatrix();
}

}  // namespace

bool PerturbationOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  if (!(std::isfinite(time_scale_min) && time_scale_min > 0.0 && std::isfinite(time_scale_max) &&
        time_scale_max >= time_scale_min)) {
    return fail("time scale range must satisfy 0 < min <= max");
  }
  if (!non_negative(position_sigma)) return fail("position_sigma must be >= 0 (m)");
  if (!non_negative(orientation_sigma)) return fail("orientation_sigma must be >= 0 (rad)");
  if (!non_negative(finger_sigma)) return fail("finger_sigma must be >= 0 (rad)");
  if (!(std::isfinite(knot_interval) && knot_interval > 0.0)) {
    return fail("knot_interval must be positive (s)");
  }
  return physics.IsValid(why);
}

PerturbedTrajectory PerturbTrajectory(const RobotModel& robot, const JointTrajectory& nominal,
                                      const PerturbationOptions& options, SplitMix64& rng) {
  RequireValid(options, "invalid perturbation option");
  if (nominal.samples.empty()) throw InputError("the trajectory has no samples");
  PerturbedTrajectory out;
  out.time_scale = options.time_scale_min == options.time_scale_max
                       ? options.time_scale_min
                       : rng.Uniform(options.time_scale_min, options.time_scale_max);

  // knots on the nominal time line.
  std::vector<double> knot_times;
  if (!nominal.waypoints.empty()) {
    for (const WristWaypoint& w : nominal.waypoints) knot_times.push_back(w.t);
  } else {
    const int n = static_cast<int>(std::ceil(nominal.duration() / options.knot_interval - 1e-9));
    for (int k = 0; k <= n; ++k) {
      knot_times.push_back(std::min(k * options.knot_interval, nominal.duration()));
    }
    knot_times.erase(std::unique(knot_times.begin(), knot_times.end()), knot_times.end());
  }
  std::vector<KnotNoise> knots;
  for (double t : knot_times) {
    KnotNoise k;
    k.t = t;
    for (int i = 0; i < 3; ++i) k.dp[i] = options.position_sigma * rng.Normal();
    for (int i = 0; i < 3; ++i) k.dr[i] = options.orientation_sigma * rng.Normal();
    for (int i = 0; i < kHandDof; ++i) k.df[i] = options.finger_sigma * rng.Normal();
    knots.push_back(k);
  }

  const HandModel& hand = robot.hand;
  JointTrajectory& traj = out.trajectory;
  traj.theta_deg = nominal.theta_deg;
  traj.object_xy = nominal.object_xy;
  Vector7d q_prev = nominal.samples.front().arm;
  for (size_t i = 0; i < nominal.samples.size(); ++i) {
    const TrajectorySample& s = nominal.samples[i];
    const KnotNoise noise = NoiseAt(knots, s.t);
    const Eigen::Isometry3d X = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
    Eigen::Isometry3d X_pert = Eigen::Isometry3d::Identity();
    X_pert.linear() = ExpRotation(noise.dr) * X.linear();
    X_pert.translation() = X.translation() + noise.dp;
    const std::optional<Vector7d> q = SolveWristPose(robot, X_pert, BranchOf(robot.arm, s.arm),
                                                     ArmAngleOf(robot.arm, s.arm), q_prev);
    if (!q) {
      out.message = "perturbed wrist pose of sample " + std::to_string(i) +
                    " (t = " + std::to_string(s.t * out.time_scale) +
                    " s) has no IK solution within the joint limits";
      return out;
    }
    TrajectorySample p;
    p.t = s.t * out.time_scale;
    p.arm = *q;
    p.hand = (s.hand + noise.df).cwiseMax(hand.lower()).cwiseMin(hand.upper());
    traj.samples.push_back(p);
    q_prev = *q;
  }
  for (const WristWaypoint& w : nominal.waypoints) {
    const KnotNoise noise = NoiseAt(knots, w.t);
    WristWaypoint p = w;
    p.t = w.t * out.time_scale;
    p.p_WH += noise.dp;
    p.q_WH = Eigen::Quaterniond(ExpRotation(noise.dr) * w.q_WH.toRotationMatrix()).normalized();
    traj.waypoints.push_back(p);
  }
  out.ok = true;
  return out;
}

}  // namespace graspsynth
