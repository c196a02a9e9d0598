#include "kinematics/arm_model.hpp"

#include <cmath>
#include <sstream>
#include <utility>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

// standard DH twist angles of the PA-10 pattern (reference/robot.md 1.3).
constexpr std::array<double, kArmDof> kAlpha = {-M_PI / 2, M_PI / 2, -M_PI / 2, M_PI / 2,
                                                -M_PI / 2, M_PI / 2, 0.0};
// tolerance on the geometric checks of a description, metres.
constexpr double kGeometryTol = 1e-6;

struct Line {
  Eigen::Vector3d origin;
  Eigen::Vector3d direction;  // unit
};

double DistanceToLine(const Line& line, const Eigen::Vector3d& p) {
  const Eigen::Vector3d w = p - line.origin;
  return (w - w.dot(line.direction) * line.direction).norm();
}

// Intersection of two joint axes; throws naming both joints when they are parallel or skew.
Eigen::Vector3d IntersectAxes(const std::string& source, const Line& a, const std::string& name_a,
                              const Line& b, const std::string& name_b) {
  const Eigen::Vector3d w = a.origin - b.origin;
  const double c = a.direction.dot(b.direction);
  const double denom = 1.0 - c * c;
  if (denom < 1e-12) {
    throw InputError(source + ": joint axes '" + name_a + "' and '" + name_b +
                     "' are parallel at the zero configuration; an SRS arm needs them to cross");
  }
  const double d = a.direction.dot(w);
  const double e = b.direction.dot(w);
  const double s = (c * e - d) / denom;
  const double t = (e - c * d) / denom;
  const Eigen::Vector3d pa = a.origin + s * a.direction;
  const Eigen::Vector3d pb = b.origin + t * b.direction;
  if ((pa - pb).norm() > kGeometryTol) {
    std::ostringstream msg;
    msg << source << ": joint axes '" << name_a << "' and '" << name_b << "' miss each other by "
        << (pa - pb).norm() << " m; an SRS arm needs them to intersect (all DH a_i = 0)";
    throw InputError(msg.str());
  }
  return 0.5 * (pa + pb);
}

void RequireOnAxis(const std::string& source, const Line& axis, const std::string& joint,
                   const Eigen::Vector3d& p, const std::string& point_name) {
  const double miss = DistanceToLine(axis, p);
  if (miss > kGeometryTol) {
    std::ostringstream msg;
    msg << source << ": joint axis '" << joint << "' misses the " << point_name << " by " << miss
        << " m; the arm is not a spherical-revolute-spherical chain";
    throw InputError(msg.str());
  }
}

Eigen::Isometry3d JointMotion(const RevoluteJoint& joint, double q) {
  Eigen::Isometry3d X = joint.X_PJ;
  X.rotate(Eigen::AngleAxisd(q, joint.axis_J));
  return X;
}

// A fixed set of configurations, spread over the joint ranges, used to compare the
// description's chain with the DH chain. Deterministic (no global random state).
std::array<Vector7d, 16> ProbeConfigurations() {
  std::array<Vector7d, 16> probes;
  uint64_t state = 0x9e3779b97f4a7c15ull;
  for (auto& q : probes) {
    for (int i = 0; i < kArmDof; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      q[i] = (static_cast<double>(state >> 11) / 9007199254740992.0 - 0.5) * 2.0 * M_PI;
    }
  }
  return probes;
}

}  // namespace

ArmModel::ArmModel(std::string source, RigidLink base, std::array<RevoluteJoint, kArmDof> joints,
                   std::array<RigidLink, kArmDof> links)
    : source_(std::move(source)),
      base_(std::move(base)),
      joints_(std::move(joints)),
      links_(std::move(links)) {
  for (int i = 0; i < kArmDof; ++i) {
    const RevoluteJoint& j = joints_[i];
    std::ostringstream where;
    where << source_ << ": arm joint '" << j.name << "'";
    if (!(j.lower < j.upper)) {
      throw InputError(where.str() + " has an empty position range [" + std::to_string(j.lower) +
                       ", " + std::to_string(j.upper) + "] rad");
    }
    if (!(j.max_velocity > 0.0)) {
      throw InputError(where.str() + " needs a positive velocity limit, has " +
                       std::to_string(j.max_velocity));
    }
    if (!(j.max_effort > 0.0)) {
      throw InputError(where.str() + " needs a positive effort limit, has " +
                       std::to_string(j.max_effort));
    }
    if (std::abs(j.axis_J.norm() - 1.0) > 1e-9) {
      throw InputError(where.str() + " has an axis that is not a unit vector");
    }
    lower_[i] = j.lower;
    upper_[i] = j.upper;
    max_velocity_[i] = j.max_velocity;
    max_effort_[i] = j.max_effort;
  }

  // joint axes in world at the zero configuration.
  std::array<Line, kArmDof> axes;
  Eigen::Isometry3d X_WL = Eigen::Isometry3d::Identity();
  for (int i = 0; i < kArmDof; ++i) {
    const Eigen::Isometry3d X_WJ = X_WL * joints_[i].X_PJ;
    axes[i] = {X_WJ.translation(), (X_WJ.linear() * joints_[i].axis_J).normalized()};
    X_WL = X_WJ;
  }
  const Eigen::Vector3d p_WF = X_WL.translation();
  const auto name = [this](int i) { return joints_[i].name; };

  // S1 must be the vertical axis through the base origin (DH d_1 along base z).
  if (axes[0].direction.cross(Eigen::Vector3d::UnitZ()).norm() > 1e-9 ||
      DistanceToLine(axes[0], Eigen::Vector3d::Zero()) > kGeometryTol) {
    throw InputError(source_ + ": the first arm joint '" + name(0) +
                     "' must turn about the vertical axis through the base origin");
  }
  const Eigen::Vector3d p_shoulder = IntersectAxes(source_, axes[0], name(0), axes[1], name(1));
  RequireOnAxis(source_, axes[2], name(2), p_shoulder, "shoulder centre");
  const Eigen::Vector3d p_elbow = IntersectAxes(source_, axes[2], name(2), axes[3], name(3));
  RequireOnAxis(source_, axes[4], name(4), p_elbow, "elbow");
  const Eigen::Vector3d p_wrist = IntersectAxes(source_, axes[4], name(4), axes[5], name(5));
  RequireOnAxis(source_, axes[6], name(6), p_wrist, "wrist centre");
  RequireOnAxis(source_, axes[6], name(6), p_WF, "flange origin");

  lengths_.d_bs = p_shoulder.norm();
  lengths_.d_se = (p_elbow - p_shoulder).norm();
  lengths_.d_ew = (p_wrist - p_elbow).norm();
  lengths_.d_wt = (p_WF - p_wrist).norm();
  if (lengths_.d_se < kGeometryTol || lengths_.d_ew < kGeometryTol) {
    throw InputError(source_ + ": the arm has a zero upper-arm or forearm length");
  }

  // the IK uses the DH table; the description must describe the same chain, signs included.
  ArmFrames frames;
  for (const Vector7d& q : ProbeConfigurations()) {
    ArmLinkFrames(*this, q, &frames);
    const Eigen::Isometry3d X_dh = DhFlangePose(lengths_, q);
    const double dp = (frames.X_WL[kArmDof].translation() - X_dh.translation()).norm();
    const double dr = (frames.X_WL[kArmDof].linear() - X_dh.linear()).norm();
    if (dp > kGeometryTol || dr > 1e-6) {
      std::ostringstream msg;
      msg << source_
          << ": the arm chain does not follow the standard DH table of the PA-10 "
             "(reference/robot.md 1.3) with the lengths read from it (d_bs "
          << lengths_.d_bs << ", d_se " << lengths_.d_se << ", d_ew " << lengths_.d_ew << ", d_wt "
          << lengths_.d_wt << " m): at q = [" << q.transpose()
          << "] the flange differs by " << dp
          << " m; check the joint axis directions, the joint order and the flange frame";
      throw InputError(msg.str());
    }
  }
}

ArmModel ArmModel::FromDh(const SrsLengths& lengths, const Vector7d& lower, const Vector7d& upper,
                          const Vector7d& max_velocity, const Vector7d& max_effort) {
  static const std::array<const char*, kArmDof> kNames = {"S1", "S2", "S3", "E1",
                                                          "E2", "W1", "W2"};
  const std::array<double, kArmDof> d = {lengths.d_bs, 0.0, lengths.d_se, 0.0,
                                         lengths.d_ew, 0.0, lengths.d_wt};
  std::array<RevoluteJoint, kArmDof> joints;
  std::array<RigidLink, kArmDof> links;
  for (int i = 0; i < kArmDof; ++i) {
    // modified DH: X_PJ = Rx(alpha_{i-1}) Tz(d_i); the joint turns about its z axis.
    const double alpha_prev = i == 0 ? 0.0 : kAlpha[i - 1];
    const Eigen::AngleAxisd rx(alpha_prev, Eigen::Vector3d::UnitX());
    RevoluteJoint& j = joints[i];
    j.name = kNames[i];
    j.X_PJ = Eigen::Isometry3d::Identity();
    j.X_PJ.linear() = rx.toRotationMatrix();
    j.X_PJ.translation() = rx * Eigen::Vector3d(0.0, 0.0, d[i]);
    j.axis_J = Eigen::Vector3d::UnitZ();
    j.lower = lower[i];
    j.upper = upper[i];
    j.max_velocity = max_velocity[i];
    j.max_effort = max_effort[i];
    links[i].name = std::string("link") + std::to_string(i + 1);
  }
  return ArmModel("DH table", RigidLink{"base", {}, {}}, joints, links);
}

bool ArmModel::WithinLimits(const Eigen::Ref<const Vector7d>& q, double tol) const {
  return ((q.array() >= lower_.array() - tol) && (q.array() <= upper_.array() + tol)).all();
}

void ArmLinkFrames(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q, ArmFrames* frames) {
  frames->X_WL[0] = Eigen::Isometry3d::Identity();
  for (int i = 0; i < kArmDof; ++i) {
    frames->X_WL[i + 1] = frames->X_WL[i] * JointMotion(arm.joint(i), q[i]);
  }
}

Eigen::Isometry3d ArmFlangePose(const ArmModel& arm, const Eigen::Ref<const Vector7d>& q) {
  return DhFlangePose(arm.lengths(), q);
}

Eigen::Isometry3d DhFlangePose(const SrsLengths& lengths, const Eigen::Ref<const Vector7d>& q) {
  const std::array<double, kArmDof> d = {lengths.d_bs, 0.0, lengths.d_se, 0.0,
                                         lengths.d_ew, 0.0, lengths.d_wt};
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int i = 0; i < kArmDof; ++i) {
    // T_i = Rz(q_i) Tz(d_i) Rx(alpha_i): the offset d_i runs along the current z axis.
    p += d[i] * R.col(2);
    const double c = std::cos(q[i]);
    const double s = std::sin(q[i]);
    const double ca = std::cos(kAlpha[i]);
    const double sa = std::sin(kAlpha[i]);
    Eigen::Matrix3d T;
    T << c, -s * ca, s * sa, s, c * ca, -c * sa, 0.0, sa, ca;
    R = R * T;
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = R;
  X.translation() = p;
  return X;
}

}  // namespace graspsynth
