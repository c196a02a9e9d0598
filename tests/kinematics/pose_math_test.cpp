#include "kinematics/pose_math.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using testing::MatricesNear;

Eigen::Quaterniond RandomQuaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  return q.normalized();
}

Eigen::Vector3d RandomVector(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

TEST(Slerp, EndpointsAreTheInputs) {
  std::mt19937_64 rng(1);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Quaterniond a = RandomQuaternion(rng);
    const Eigen::Quaterniond b = RandomQuaternion(rng);
    EXPECT_LT(AngleBetween(Slerp(a, b, 0.0), a), 1e-12);
    EXPECT_LT(AngleBetween(Slerp(a, b, 1.0), b), 1e-7);
    EXPECT_NEAR(Slerp(a, b, 0.37).norm(), 1.0, 1e-14);
  }
}

TEST(Slerp, ConstantAngularRateAlongTheShorterArc) {
  std::mt19937_64 rng(2);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Quaterniond a = RandomQuaternion(rng);
    const Eigen::Quaterniond b = RandomQuaternion(rng);
    const double total = AngleBetween(a, b);
    ASSERT_LE(total, M_PI + 1e-12);
    for (double t : {0.1, 0.25, 0.5, 0.9}) {
      const Eigen::Quaterniond q = Slerp(a, b, t);
      EXPECT_NEAR(AngleBetween(a, q), t * total, 1e-9);
      EXPECT_NEAR(AngleBetween(q, b), (1.0 - t) * total, 1e-9);
    }
  }
}

TEST(Slerp, AntipodalInputGivesTheSameRotations) {
  std::mt19937_64 rng(3);
  for (int k = 0; k < 200; ++k) {
    const Eigen::Quaterniond a = RandomQuaternion(rng);
    const Eigen::Quaterniond b = RandomQuaternion(rng);
    Eigen::Quaterniond minus_b;
    minus_b.coeffs() = -b.coeffs();
    for (double t : {0.0, 0.3, 0.7, 1.0}) {
      EXPECT_LT(AngleBetween(Slerp(a, b, t), Slerp(a, minus_b, t)), 1e-9);
    }
  }
}

TEST(Slerp, AboutOneAxisTurnsByTheFraction) {
  const Eigen::Quaterniond a(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond b(Eigen::AngleAxisd(1.4, Eigen::Vector3d::UnitZ()));
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(0.2 + 0.25 * 1.2, Eigen::Vector3d::UnitZ()));
  EXPECT_LT(AngleBetween(Slerp(a, b, 0.25), expected), 1e-12);
  // identical inputs stay put without dividing by sin(0).
  EXPECT_LT(AngleBetween(Slerp(a, a, 0.5), a), 1e-15);
}

TEST(Aslerp, EndpointsAndNormBlendOfEquationTwo) {
  std::mt19937_64 rng(4);
  for (int k = 0; k < 1000; ++k) {
    const Eigen::Vector3d p1 = RandomVector(rng, 0.5);
    const Eigen::Vector3d p2 = RandomVector(rng, 0.5);
    EXPECT_TRUE(MatricesNear(Aslerp(p1, p2, 0.0), p1, 1e-12));
    EXPECT_TRUE(MatricesNear(Aslerp(p1, p2, 1.0), p2, 1e-9));
    for (double t : {0.2, 0.5, 0.8}) {
      EXPECT_NEAR(Aslerp(p1, p2, t).norm(), (1.0 - t) * p1.norm() + t * p2.norm(), 1e-12);
    }
  }
}

TEST(Aslerp, DirectionTurnsAtConstantRate) {
  std::mt19937_64 rng(5);
  for (int k = 0; k < 500; ++k) {
    const Eigen::Vector3d p1 = RandomVector(rng, 0.5);
    const Eigen::Vector3d p2 = RandomVector(rng, 0.5);
    const double total = std::acos(p1.normalized().dot(p2.normalized()));
    const Eigen::Vector3d p = Aslerp(p1, p2, 0.3);
    EXPECT_NEAR(std::acos(std::clamp(p.normalized().dot(p1.normalized()), -1.0, 1.0)), 0.3 * total,
                1e-7);
    // the interpolated direction stays in the plane of the two inputs.
    EXPECT_NEAR(p.dot(p1.cross(p2).normalized()), 0.0, 1e-12);
  }
}

TEST(Aslerp, TablePlaneExampleFromThePaper) {
  // grasp positions of Table I at theta 20 and 30 deg: (d, eta) = (0.378, -75.3), (0.371, -73.0).
  const auto polar = [](double d, double eta_deg) {
    const double eta = eta_deg * M_PI / 180.0;
    return Eigen::Vector3d(d * std::cos(eta), d * std::sin(eta), 0.0);
  };
  const Eigen::Vector3d p = Aslerp(polar(0.378, -75.3), polar(0.371, -73.0), 0.5);
  EXPECT_NEAR(p.norm(), 0.3745, 1e-12);
  EXPECT_NEAR(std::atan2(p.y(), p.x()) * 180.0 / M_PI, -74.15, 1e-9);
}

TEST(Aslerp, DegenerateInputsFallBackToTheLinearBlend) {
  const Eigen::Vector3d p(0.3, 0.0, 0.0);
  EXPECT_TRUE(MatricesNear(Aslerp(Eigen::Vector3d::Zero(), p, 0.5), 0.5 * p, 1e-15));
  EXPECT_TRUE(MatricesNear(Aslerp(p, -p, 0.25), 0.5 * p, 1e-15));
}

TEST(ConvexBlend, IsEquationFour) {
  HandVector f1 = HandVector::Constant(0.2);
  HandVector f2 = HandVector::LinSpaced(0.0, 1.5);
  const HandVector f = ConvexBlend(f1, f2, 0.25);
  EXPECT_TRUE(MatricesNear(f, 0.75 * f1 + 0.25 * f2, 1e-15));
  EXPECT_TRUE(MatricesNear(ConvexBlend(f1, f2, 0.0), f1, 0.0));
  EXPECT_TRUE(MatricesNear(ConvexBlend(f1, f2, 1.0), f2, 0.0));
}

TEST(DistanceBetween, MeasuresTranslationAndRotation) {
  Eigen::Isometry3d a = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d b = Eigen::Isometry3d::Identity();
  b.translate(Eigen::Vector3d(0.03, 0.04, 0.0));
  b.rotate(Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()));
  const PoseDistance d = DistanceBetween(a, b);
  EXPECT_NEAR(d.translation, 0.05, 1e-15);
  EXPECT_NEAR(d.rotation, 0.5, 1e-12);
}

TEST(Canonical, HasNonNegativeScalarPart) {
  Eigen::Quaterniond q(-0.5, 0.5, -0.5, 0.5);
  const Eigen::Quaterniond c = Canonical(q);
  EXPECT_GE(c.w(), 0.0);
  EXPECT_LT(AngleBetween(c, q), 1e-15);
}

TEST(PoseFrom, MapsThePointsAsTranslationAfterRotation) {
  const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const Eigen::Isometry3d X = PoseFrom(Eigen::Vector3d(1.0, 2.0, 3.0), q);
  EXPECT_TRUE(X.translation().isApprox(Eigen::Vector3d(1.0, 2.0, 3.0)));
  // x rotated a quarter turn about z is y, then moved by the translation.
  EXPECT_LT((X * Eigen::Vector3d::UnitX() - Eigen::Vector3d(1.0, 3.0, 3.0)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(X.matrix()(3, 3), 1.0);
}

}  // namespace
}  // namespace graspsynth
