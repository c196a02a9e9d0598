#include "kinematics/pose_math.hpp"

#include <cmath>

namespace graspsynth {
namespace {

// below this angle sin(angle) ~ angle and the slerp weights lose precision; a normalized
// linear blend is then exact to double precision.
constexpr double kSmallAngle = 1e-9;

// Great-circle interpolation between unit 4-vectors (or 3-vectors) a and b whose angle is
// `angle` in (0, pi).
template <typename V>
V ArcBlend(const V& a, const V& b, double angle, double t) {
  const double s = std::sin(angle);
  return (std::sin((1.0 - t) * angle) / s) * a + (std::sin(t * angle) / s) * b;
}

}  // namespace

Eigen::Quaterniond Slerp(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2, double t) {
  Eigen::Vector4d a = q1.normalized().coeffs();
  Eigen::Vector4d b = q2.normalized().coeffs();
  if (a.dot(b) < 0.0) b = -b;  // shorter arc
  // the angle from atan2 stays accurate near 0 and pi, unlike acos(dot).
  const double angle = 2.0 * std::atan2((a - b).norm(), (a + b).norm());
  Eigen::Vector4d c;
  if (angle < kSmallAngle) {
    c = ((1.0 - t) * a + t * b).normalized();
  } else {
    c = ArcBlend(a, b, angle, t).normalized();
  }
  Eigen::Quaterniond q;
  q.coeffs() = c;
  return q;
}

Eigen::Vector3d Aslerp(const Eigen::Vector3d& p1, const Eigen::Vector3d& p2, double t) {
  const double n1 = p1.norm();
  const double n2 = p2.norm();
  if (n1 == 0.0 || n2 == 0.0) return (1.0 - t) * p1 + t * p2;
  const Eigen::Vector3d a = p1 / n1;
  const Eigen::Vector3d b = p2 / n2;
  const double angle = 2.0 * std::atan2((a - b).norm(), (a + b).norm());
  const double s = (1.0 - t) * n1 + t * n2;  // eq. 2
  if (angle < kSmallAngle) return s * ((1.0 - t) * a + t * b).normalized();
  if (M_PI - angle < 1e-9) return (1.0 - t) * p1 + t * p2;
  return s * ArcBlend(a, b, angle, t).normalized();  // eq. 1
}

double AngleBetween(const Eigen::Quaterniond& q1, const Eigen::Quaterniond& q2) {
  const Eigen::Quaterniond d = q1.normalized().conjugate() * q2.normalized();
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

PoseDistance DistanceBetween(const Eigen::Isometry3d& X_a, const Eigen::Isometry3d& X_b) {
  PoseDistance d;
  d.translation = (X_a.translation() - X_b.translation()).norm();
  d.rotation = AngleBetween(Eigen::Quaterniond(X_a.linear()), Eigen::Quaterniond(X_b.linear()));
  return d;
}

Eigen::Quaterniond Canonical(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond c = q.normalized();
  if (c.w() < 0.0) c.coeffs() = -c.coeffs();
  return c;
}

Eigen::Quaterniond CanonicalForFile(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond r = q;
  const double norm = r.norm();
  if (std::abs(norm - 1.0) > 1e-15) r.coeffs() /= norm;
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();
  return r;
}

Eigen::Isometry3d PoseFrom(const Eigen::Vector3d& p, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q.toRotationMatrix();
  X.translation() = p;
  return X;
}

}  // namespace graspsynth
