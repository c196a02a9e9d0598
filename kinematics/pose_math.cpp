#include "kinematics/pose_math.hpp"

#include <cmath>

#include "common/demand.hpp"

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

namespace {

// The weighted Karcher mean of unit vectors x_i (3 or 4 components) from the start m:
// m <- exp_m(sum_i w_i log_m(x_i)) until the step is below 1e-15 rad (at most 100 steps).
template <typename V>
V SphereMean(const std::vector<V>& x, const std::vector<double>& w, V m) {
  for (int iteration = 0; iteration < 100; ++iteration) {
    V step = V::Zero();
    for (size_t i = 0; i < x.size(); ++i) {
      if (w[i] == 0.0) continue;
      const V tangent = x[i] - m.dot(x[i]) * m;
      const double n = tangent.norm();
      if (n == 0.0) continue;
      const double angle = std::atan2(n, m.dot(x[i]));
      step += w[i] * (angle / n) * tangent;
    }
    const double a = step.norm();
    if (a < 1e-15) break;
    m = (std::cos(a) * m + (std::sin(a) / a) * step).normalized();
  }
  return m;
}

// The index of the heaviest weight (the first on ties).
size_t Heaviest(const std::vector<double>& w) {
  size_t k = 0;
  for (size_t i = 1; i < w.size(); ++i) {
    if (w[i] > w[k]) k = i;
  }
  return k;
}

void DemandWeights(size_t n, const std::vector<double>& w) {
  GS_DEMAND(n > 0 && w.size() == n, "one weight per value, at least one");
  double sum = 0.0;
  for (double v : w) {
    GS_DEMAND(v >= 0.0, "a negative weight");
    sum += v;
  }
  GS_DEMAND(std::abs(sum - 1.0) <= 1e-9, "weights that do not sum to 1");
}

}  // namespace

Eigen::Quaterniond WeightedSlerp(const std::vector<Eigen::Quaterniond>& q,
                                 const std::vector<double>& w) {
  DemandWeights(q.size(), w);
  const size_t k = Heaviest(w);
  Eigen::Vector4d m = q[k].normalized().coeffs();
  if (w[k] == 1.0) {
    Eigen::Quaterniond out;
    out.coeffs() = m;
    return out;
  }
  std::vector<Eigen::Vector4d> x;
  for (const Eigen::Quaterniond& qi : q) {
    Eigen::Vector4d c = qi.normalized().coeffs();
    if (c.dot(m) < 0.0) c = -c;  // shorter arc
    x.push_back(c);
  }
  Eigen::Quaterniond out;
  out.coeffs() = SphereMean(x, w, m);
  return out;
}

Eigen::Vector3d WeightedAslerp(const std::vector<Eigen::Vector3d>& p,
                               const std::vector<double>& w) {
  DemandWeights(p.size(), w);
  const size_t k = Heaviest(w);
  if (w[k] == 1.0) return p[k];
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < p.size(); ++i) linear += w[i] * p[i];
  double s = 0.0;  // eq. 2: the weighted norm
  std::vector<Eigen::Vector3d> x;
  for (size_t i = 0; i < p.size(); ++i) {
    const double n = p[i].norm();
    if (n == 0.0) {
      if (w[i] > 0.0) return linear;
      x.push_back(Eigen::Vector3d::Zero());  // no weight: never read
      continue;
    }
    s += w[i] * n;
    x.push_back(p[i] / n);
  }
  for (size_t i = 0; i < x.size(); ++i) {
    for (size_t j = i + 1; j < x.size(); ++j) {
      if (w[i] > 0.0 && w[j] > 0.0 && x[i].dot(x[j]) < -1.0 + 1e-12) return linear;
    }
  }
  return s * SphereMean(x, w, x[k]);
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
