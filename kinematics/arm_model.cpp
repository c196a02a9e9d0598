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
// tolerance on the axis directions of a description against the DH table's, rad.
constexpr double kAxisTol = 1e-6;
// offsets within this of 0 (rad) and flange turns within this of I are taken as exactly zero
// and I, so that a description of the DH table itself gets the identity map (its probe check
// below still compares the chains within the SRS tolerance).
constexpr double kSnapTol = 1e-9;

// "0.0123 m (12.3 mm)"
std::string MetresAndMm(double metres) {
  std::ostringstream out;
  out << metres << " m (" << metres * 1e3 << " mm)";
  return out.str();
}

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
                              const Line& b, const std::string& name_b, double tol) {
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
  if ((pa - pb).norm() > tol) {
    std::ostringstream msg;
    msg << source << ": joint axes '" << name_a << "' and '" << name_b << "' miss each other by "
        << MetresAndMm((pa - pb).norm()) << ", more than the SRS tolerance " << tol
        << " m; an SRS arm needs them to intersect (all DH a_i = 0)";
    throw InputError(msg.str());
  }
  return 0.5 * (pa + pb);
}

void RequireOnAxis(const std::string& source, const Line& axis, const std::string& joint,
                   const Eigen::Vector3d& p, const std::string& point_name, double tol) {
  const double miss = DistanceToLine(axis, p);
  if (miss > tol) {
    std::ostringstream msg;
    msg << source << ": joint axis '" << joint << "' misses the " << point_name << " by "
        << MetresAndMm(miss) << ", more than the SRS tolerance " << tol
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

// Angle (rad) between the line along `a` and the line along `b` (unit vectors), in [0, pi/2].
double LineAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::abs(a.dot(b)));
}

[[noreturn]] void ThrowAxisMiss(const std::string& source, const std::string& joint, int index,
                                double angle) {
  std::ostringstream msg;
  msg << source << ": arm joint '" << joint << "': its axis at q = 0 is " << angle * 180.0 / M_PI
      << " deg (" << angle << " rad) off axis " << index + 1
      << " of the DH table of reference/robot.md 1.3 for every sign and offset of the joints "
         "before it (tolerance "
      << kAxisTol << " rad); the chain is not that DH pattern";
  throw InputError(msg.str());
}

// The DhJointMap of a chain from its axes at q = 0 (world), the directions of its links and the
// flange's rotation at q = 0, walking the DH table: joint i's sign is its axis against DH axis
// i with the offsets found so far; offset i turns DH axis i + 1 onto the chain's axis i + 1 (it
// must be perpendicular to axis i), pointing along the next link where there is one (after S2,
// E1, W1: the upper arm, the forearm and the wrist-flange segment run along axes 3, 5, 7), else
// in (-pi/2, pi/2] (after S1, S3, E2: the other choice is the same chain on the other
// gc2/gc4/gc6 branch). The last offset is 0: the flange's turn about A7 is R_7F's. The link
// directions only pick a side, so a chain within a loose SRS tolerance still maps; the probe
// comparison in the constructor checks the positions.
DhJointMap DeriveDhMap(const std::string& source, const std::array<RevoluteJoint, kArmDof>& joints,
                       const std::array<Line, kArmDof>& axes,
                       const std::array<Eigen::Vector3d, kArmDof>& link_direction,
                       const Eigen::Matrix3d& R_WF0) {
  DhJointMap map;
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();  // DH frame i - 1 at the offsets so far
  for (int i = 0; i < kArmDof; ++i) {
    const Eigen::Vector3d z = R.col(2);
    const double miss = LineAngle(axes[i].direction, z);
    if (miss > kAxisTol) ThrowAxisMiss(source, joints[i].name, i, miss);
    map.sign[i] = axes[i].direction.dot(z) > 0.0 ? 1 : -1;
    if (i + 1 == kArmDof) break;
    // DH axis i + 1 is R Rz(o) Rx(alpha_i) e_z = R (sa sin o, -sa cos o, 0) for alpha = +-pi/2.
    const Eigen::Vector3d t = R.transpose() * axes[i + 1].direction;
    const double sa = kAlpha[i] > 0.0 ? 1.0 : -1.0;
    const double tilt = std::atan2(std::abs(t.z()), std::hypot(t.x(), t.y()));
    if (tilt > kAxisTol) ThrowAxisMiss(source, joints[i + 1].name, i + 1, tilt);
    double o = std::atan2(sa * t.x(), -sa * t.y());
    const Eigen::Vector3d l = R.transpose() * link_direction[i];
    if (link_direction[i].squaredNorm() > 0.0) {
      // DH axis i + 1 along the link: o or o + pi.
      if (sa * (std::sin(o) * l.x() - std::cos(o) * l.y()) < 0.0) o += o > 0.0 ? -M_PI : M_PI;
    } else {
      if (o > M_PI / 2) o -= M_PI;
      if (o <= -M_PI / 2) o += M_PI;
    }
    if (std::abs(o) <= kSnapTol) o = 0.0;
    map.offset[i] = o;
    R = R * Eigen::AngleAxisd(o, Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(kAlpha[i], Eigen::Vector3d::UnitX());
  }
  map.R_7F = R.transpose() * R_WF0;
  if ((map.R_7F - Eigen::Matrix3d::Identity()).norm() <= kSnapTol) {
    map.R_7F = Eigen::Matrix3d::Identity();
  }
  map.identity = map.R_7F == Eigen::Matrix3d::Identity() && (map.offset.array() == 0.0).all();
  for (const int s : map.sign) map.identity = map.identity && s == 1;
  return map;
}

// Throws InputError unless the description's chain (its link frames) and the DH table through
// the arm's DhJointMap give the same flange at a fixed set of configurations, within `tol` m
// and 1e-6 in the rotation matrix.
void RequireDhChain(const ArmModel& arm, double tol) {
  const SrsLengths& len = arm.lengths();
  // the IK uses the DH table; the description must describe the same chain through the map.
  ArmFrames frames;
  for (const Vector7d& q : ProbeConfigurations()) {
    ArmLinkFrames(arm, q, &frames);
    const Eigen::Isometry3d X_WF = frames.X_WL[kArmDof] * arm.X_7F();
    const Eigen::Isometry3d X_dh = ArmFlangePose(arm, q);
    const double dp = (X_WF.translation() - X_dh.translation()).norm();
    const double dr = (X_WF.linear() - X_dh.linear()).norm();
    if (dp > tol || dr > 1e-6) {
      std::ostringstream msg;
      msg << arm.source()
          << ": the arm chain does not follow the standard DH table of reference/robot.md 1.3 "
             "with the lengths read from it (d_bs "
          << len.d_bs << ", d_se " << len.d_se << ", d_ew " << len.d_ew << ", d_wt " << len.d_wt
          << " m) and the joint signs [";
      for (int i = 0; i < kArmDof; ++i) msg << (i ? " " : "") << arm.dh_map().sign[i];
      msg << "] and offsets [" << arm.dh_map().offset.transpose()
          << "] rad read from its axes: at q = [" << q.transpose() << "] the flange differs by "
          << MetresAndMm(dp) << " and " << dr
          << " in rotation; check the joint order, the link lengths and the flange frame";
      throw InputError(msg.str());
    }
  }
}

}  // namespace

bool ArmChainOptions::IsValid(std::string* why) const {
  std::string reason;
  if (!(srs_tolerance_m > 0.0 && srs_tolerance_m <= 0.01)) {
    reason = "srs_tolerance_m must be in (0, 0.01] m, is " + std::to_string(srs_tolerance_m);
  } else if (!X_7F.matrix().allFinite()) {
    reason = "X_7F (the flange in link 7) is not finite";
  }
  if (why != nullptr) *why = reason;
  return reason.empty();
}

Vector7d DhJointMap::ToDh(const Eigen::Ref<const Vector7d>& q) const {
  if (identity) return q;
  Vector7d q_dh;
  for (int i = 0; i < kArmDof; ++i) q_dh[i] = (sign[i] > 0 ? q[i] : -q[i]) + offset[i];
  return q_dh;
}

Vector7d DhJointMap::ToJoints(const Eigen::Ref<const Vector7d>& q_dh) const {
  if (identity) return q_dh;
  Vector7d q;
  for (int i = 0; i < kArmDof; ++i) {
    const double shifted = q_dh[i] - offset[i];
    q[i] = sign[i] > 0 ? shifted : -shifted;
  }
  return q;
}

Eigen::Isometry3d DhJointMap::FlangeToDh(const Eigen::Isometry3d& X_WF) const {
  if (identity) return X_WF;
  Eigen::Isometry3d X_W7 = X_WF;
  X_W7.linear() = X_WF.linear() * R_7F.transpose();
  return X_W7;
}

Eigen::Isometry3d DhJointMap::DhToFlange(const Eigen::Isometry3d& X_W7) const {
  if (identity) return X_W7;
  Eigen::Isometry3d X_WF = X_W7;
  X_WF.linear() = X_W7.linear() * R_7F;
  return X_WF;
}

ArmModel::ArmModel(std::string source, RigidLink base, std::array<RevoluteJoint, kArmDof> joints,
                   std::array<RigidLink, kArmDof> links, const ArmChainOptions& options)
    : source_(std::move(source)),
      base_(std::move(base)),
      joints_(std::move(joints)),
      links_(std::move(links)),
      X_7F_(options.X_7F) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError(source_ + ": " + why);
  const double tol = options.srs_tolerance_m;
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
  const Eigen::Isometry3d X_WF0 = X_WL * X_7F_;
  const Eigen::Vector3d p_WF = X_WF0.translation();
  const auto name = [this](int i) { return joints_[i].name; };

  // S1 must be the vertical axis through the base origin (DH d_1 along base z).
  if (axes[0].direction.cross(Eigen::Vector3d::UnitZ()).norm() > 1e-9 ||
      DistanceToLine(axes[0], Eigen::Vector3d::Zero()) > tol) {
    throw InputError(source_ + ": the first arm joint '" + name(0) +
                     "' must turn about the vertical axis through the base origin");
  }
  const Eigen::Vector3d p_shoulder =
      IntersectAxes(source_, axes[0], name(0), axes[1], name(1), tol);
  RequireOnAxis(source_, axes[2], name(2), p_shoulder, "shoulder centre", tol);
  const Eigen::Vector3d p_elbow = IntersectAxes(source_, axes[2], name(2), axes[3], name(3), tol);
  RequireOnAxis(source_, axes[4], name(4), p_elbow, "elbow", tol);
  const Eigen::Vector3d p_wrist = IntersectAxes(source_, axes[4], name(4), axes[5], name(5), tol);
  RequireOnAxis(source_, axes[6], name(6), p_wrist, "wrist centre", tol);
  RequireOnAxis(source_, axes[6], name(6), p_WF, "flange origin", tol);

  lengths_.d_bs = p_shoulder.norm();
  lengths_.d_se = (p_elbow - p_shoulder).norm();
  lengths_.d_ew = (p_wrist - p_elbow).norm();
  lengths_.d_wt = (p_WF - p_wrist).norm();
  if (lengths_.d_se < tol || lengths_.d_ew < tol) {
    throw InputError(source_ + ": the arm has a zero upper-arm or forearm length");
  }

  // joint signs, offsets and the flange turn against the DH table.
  std::array<Eigen::Vector3d, kArmDof> link_direction;
  for (Eigen::Vector3d& d : link_direction) d.setZero();
  link_direction[1] = (p_elbow - p_shoulder) / lengths_.d_se;
  link_direction[3] = (p_wrist - p_elbow) / lengths_.d_ew;
  if (lengths_.d_wt >= tol) link_direction[5] = (p_WF - p_wrist) / lengths_.d_wt;
  dh_map_ = DeriveDhMap(source_, joints_, axes, link_direction, X_WF0.linear());
  if (dh_map_.identity) {
    dh_lower_ = lower_;
    dh_upper_ = upper_;
  } else {
    for (int i = 0; i < kArmDof; ++i) {
      const double s = dh_map_.sign[i];
      dh_lower_[i] = (s > 0 ? lower_[i] : -upper_[i]) + dh_map_.offset[i];
      dh_upper_[i] = (s > 0 ? upper_[i] : -lower_[i]) + dh_map_.offset[i];
    }
  }

  RequireDhChain(*this, tol);
}

ArmModel ArmModel::FromDh(const SrsLengths& lengths, const Vector7d& lower, const Vector7d& upper,
                          const Vector7d& max_velocity, const Vector7d& max_effort) {
  static const std::array<const char*, kArmDof> kNames = {"S1", "S2", "S3", "E1", "E2", "W1", "W2"};
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
  const DhJointMap& map = arm.dh_map();
  if (map.identity) return DhFlangePose(arm.lengths(), q);
  return map.DhToFlange(DhFlangePose(arm.lengths(), map.ToDh(q)));
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
