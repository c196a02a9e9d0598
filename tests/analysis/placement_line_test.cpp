#include "analysis/placement_line.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinematics/types.hpp"

namespace graspsynth {
namespace {

// The wrist offsets of a known affine model (b, a_theta fixed) on a 3 x 3 grid of positions at nine
// orientations, with `noise` (m, uniform per axis) added.
std::vector<PlacementLineSample> ModelSamples(const Eigen::Vector3d& a_x,
                                              const Eigen::Vector3d& a_y, double noise) {
  const Eigen::Vector3d b(-0.05, -0.12, 0.08), a_theta(0.04, 0.03, 0.0);
  const Eigen::Vector2d reference(-0.25, 0.85);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-noise, noise);
  std::vector<PlacementLineSample> samples;
  for (double x : {-0.30, -0.25, -0.20}) {
    for (double y : {0.80, 0.85, 0.90}) {
      for (int theta = 20; theta <= 100; theta += 10) {
        PlacementLineSample s;
        s.placement = Eigen::Vector3d(x, y, theta * kDeg);
        s.wrist = b + a_x * (x - reference.x()) + a_y * (y - reference.y()) +
                  a_theta * s.placement.z() + Eigen::Vector3d(u(rng), u(rng), u(rng));
        samples.push_back(s);
      }
    }
  }
  return samples;
}

TEST(PlacementLine, RecoversAnExactAffineModel) {
  const Eigen::Vector3d a_x(0.2, -0.1, 0.0);
  const PlacementLineFit fit =
      FitPlacementLine(ModelSamples(a_x, Eigen::Vector3d(0.0, 0.1, 0.0), 0.0), WristLineOptions{});
  ASSERT_TRUE(fit.valid) << fit.message;
  EXPECT_EQ(fit.samples, 81);
  EXPECT_EQ(fit.positions, 9);
  EXPECT_NEAR(fit.reference.x(), -0.25, 1e-12);
  EXPECT_NEAR(fit.reference.y(), 0.85, 1e-12);
  EXPECT_LT((fit.a_x - a_x).norm(), 1e-8);
  EXPECT_LT((fit.a_y - Eigen::Vector3d(0.0, 0.1, 0.0)).norm(), 1e-8);
  EXPECT_LT((fit.a_theta - Eigen::Vector3d(0.04, 0.03, 0.0)).norm(), 1e-8);
  EXPECT_LT((fit.b - Eigen::Vector3d(-0.05, -0.12, 0.08)).norm(), 1e-8);
  EXPECT_LT(fit.residuals.rms_xy, 1e-9);
  EXPECT_NEAR(fit.line_angle_deg, std::atan2(0.03, 0.04) / kDeg, 1e-6);
  // without the position terms the model cannot follow the moves
  EXPECT_GT(fit.theta_only.rms_xy, 0.003);
}

TEST(PlacementLine, PositionTermsVanishWhenTheGraspMovesWithTheObject) {
  const PlacementLineFit fit = FitPlacementLine(
      ModelSamples(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.002), WristLineOptions{});
  ASSERT_TRUE(fit.valid) << fit.message;
  EXPECT_LT(fit.residuals.rms_xy, 0.003);
  EXPECT_LT(fit.a_x.norm(), 0.05);
  EXPECT_LT(fit.a_y.norm(), 0.05);
  // the theta-only model explains the noise-free part as well, up to the noise
  EXPECT_LT(fit.theta_only.rms_xy - fit.residuals.rms_xy, 0.0005);
  EXPECT_GE(fit.theta_only.rms_xy, fit.residuals.rms_xy);
}

TEST(PlacementLine, PositionsOnOneLineAreRefusedWithTheReason) {
  std::vector<PlacementLineSample> samples;
  for (const PlacementLineSample& s :
       ModelSamples(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0)) {
    if (std::abs(s.placement.y() - 0.85) < 1e-9) samples.push_back(s);
  }
  const PlacementLineFit fit = FitPlacementLine(samples, WristLineOptions{});
  EXPECT_FALSE(fit.valid);
  EXPECT_EQ(fit.positions, 3);
  EXPECT_NE(fit.message.find("not all on one line"), std::string::npos) << fit.message;
  EXPECT_FALSE(FitPlacementLine({}, WristLineOptions{}).valid);
}

TEST(PlacementLine, MeanPerPlacementAveragesTrialsAtOnePlacement) {
  PlacementLineSample a, b, c;
  a.placement = b.placement = Eigen::Vector3d(-0.25, 0.85, 0.5);
  b.placement.x() += 0.0004;  // the same position within 5 mm
  c.placement = Eigen::Vector3d(-0.25, 0.85, 0.6);
  a.wrist = Eigen::Vector3d(0.1, 0.0, 0.0);
  b.wrist = Eigen::Vector3d(0.2, 0.0, 0.0);
  const std::vector<PlacementLineSample> means = MeanPerPlacement({a, c, b, a});
  ASSERT_EQ(means.size(), 2u);
  EXPECT_EQ(means[0].trials, 3);
  EXPECT_NEAR(means[0].wrist.x(), 0.4 / 3.0, 1e-12);
  EXPECT_NEAR(means[0].placement.x(), -0.25 + 0.0004 / 3.0, 1e-12);
  EXPECT_EQ(means[1].trials, 1);
}

}  // namespace
}  // namespace graspsynth
