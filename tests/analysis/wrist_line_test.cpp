// Tests of the wrist-line fit (Ceres, CGAL cross-check), the radial model and angular ranges.

#include "analysis/wrist_line.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <random>

#include "analysis/analysis_report.hpp"
#include "tests/learning_data/demo_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using ::testing::HasSubstr;
using testing::Polar;

// Points on the line through `p0` along unit `u` at the given arc positions.
std::vector<Eigen::Vector2d> OnLine(const Eigen::Vector2d& p0, const Eigen::Vector2d& u,
                                    const std::vector<double>& s) {
  std::vector<Eigen::Vector2d> points;
  for (double si : s) points.push_back(p0 + si * u);
  return points;
}

// The paper's mean grasp positions (Table I), object-centred, m.
std::vector<Eigen::Vector2d> PaperGraspPoints() {
  std::vector<Eigen::Vector2d> points;
  for (const PaperTableRow& row : PaperTableI()) {
    points.push_back(Polar(row.grasp_d, row.grasp_eta_deg));
  }
  return points;
}

std::vector<double> PaperTheta() {
  std::vector<double> theta;
  for (const PaperTableRow& row : PaperTableI()) theta.push_back(row.theta_deg * kDeg);
  return theta;
}

TEST(WristLine, CeresAndCgalAgreeOnExactCollinearData) {
  const Eigen::Vector2d p0(0.10, -0.35);
  const Eigen::Vector2d u = Eigen::Vector2d(0.8, 0.6);
  const std::vector<Eigen::Vector2d> points =
      OnLine(p0, u, {-0.21, -0.1, -0.07, 0.0, 0.013, 0.05, 0.11, 0.2});
  const WristLineResult r = FitWristLine(points, {});
  ASSERT_EQ(r.termination, WristLineTermination::kConverged) << r.message;
  EXPECT_TRUE(r.usable());
  EXPECT_LT(r.residuals.max, 1e-12);
  EXPECT_LT(r.residuals.rms, 1e-12);
  ASSERT_EQ(r.residuals.per_point.size(), points.size());
  // the line found is the true one, oriented from the first point toward the last.
  EXPECT_TRUE(testing::MatricesNear(r.line.direction, u, 1e-9));
  EXPECT_LT(r.line.Distance(p0), 1e-12);
  EXPECT_NEAR(r.line.direction.norm(), 1.0, 1e-15);
  // CGAL's fit is the same line.
  EXPECT_LT(r.cgal_difference.angle, 1e-6);
  EXPECT_LT(r.cgal_difference.offset, 1e-6);
  EXPECT_TRUE(r.cgal_agrees);
  EXPECT_LT(CompareLines(r.line, r.cgal_line).angle, 1e-9);
  EXPECT_LT(r.cgal_residuals.max, 1e-9);
  EXPECT_THAT(r.BriefReport(), HasSubstr("CGAL agrees"));
}

TEST(WristLine, CeresAndCgalAgreeOnNoisyData) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.003);
  std::uniform_real_distribution<double> along(-0.2, 0.2);
  const Eigen::Vector2d p0(-0.05, -0.33);
  const Eigen::Vector2d u = Eigen::Vector2d(1.0, 0.9).normalized();
  const Eigen::Vector2d n(-u.y(), u.x());
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 60; ++i) points.push_back(p0 + along(rng) * u + noise(rng) * n);
  const WristLineResult r = FitWristLine(points, {});
  ASSERT_TRUE(r.usable()) << r.message;
  // two exact solutions of the same least-squares problem: they agree to solver precision.
  EXPECT_LT(r.cgal_difference.angle, 1e-7);
  EXPECT_LT(r.cgal_difference.offset, 1e-8);
  EXPECT_TRUE(r.cgal_agrees);
  EXPECT_NEAR(r.residuals.rms, r.cgal_residuals.rms, 1e-10);
  // and near the true line.
  EXPECT_LT(CompareLines(r.line, Line2d{p0, u}).angle, 2.0 * kDeg);
  EXPECT_LT(r.line.Distance(p0), 0.003);
  EXPECT_GT(r.residuals.rms, 0.0015);
  EXPECT_LT(r.residuals.rms, 0.0045);
}

TEST(WristLine, RobustLossIgnoresAPlantedOutlier) {
  const Eigen::Vector2d p0(0.0, -0.34);
  const Eigen::Vector2d u = Eigen::Vector2d(1.0, 0.35).normalized();
  const Eigen::Vector2d n(-u.y(), u.x());
  std::vector<Eigen::Vector2d> points =
      OnLine(p0, u, {-0.16, -0.12, -0.08, -0.04, 0.0, 0.04, 0.08, 0.12, 0.16});
  points.insert(points.begin() + 6, p0 + 0.06 * u + 0.08 * n);  // 8 cm off the line
  const Line2d truth{p0, u};

  const WristLineResult plain = FitWristLine(points, {});
  ASSERT_TRUE(plain.usable());
  const LineDifference plain_error = CompareLines(plain.line, truth);
  EXPECT_GT(plain_error.angle + plain_error.offset, 0.005);  // the outlier drags the plain fit

  WristLineOptions cauchy;
  cauchy.loss = LineLoss::kCauchy;
  cauchy.loss_scale = 0.005;
  const WristLineResult robust = FitWristLine(points, cauchy);
  ASSERT_EQ(robust.termination, WristLineTermination::kConverged) << robust.message;
  const LineDifference robust_error = CompareLines(robust.line, truth);
  EXPECT_LT(robust_error.angle, 1e-3);
  EXPECT_LT(robust_error.offset, 1e-4);
  EXPECT_NEAR(robust.residuals.per_point[6], 0.08, 1e-3);  // the outlier keeps its residual
  EXPECT_EQ(robust.loss, LineLoss::kCauchy);
  // the plain fit and the cross-check are still reported beside the robust line.
  EXPECT_LT(CompareLines(robust.plain_line, plain.line).angle, 1e-9);
  EXPECT_TRUE(robust.cgal_agrees);

  WristLineOptions huber = cauchy;
  huber.loss = LineLoss::kHuber;
  const WristLineResult bounded = FitWristLine(points, huber);
  ASSERT_TRUE(bounded.usable());
  const LineDifference huber_error = CompareLines(bounded.line, truth);
  // Huber bounds the outlier's pull to about loss_scale / n instead of ignoring it.
  EXPECT_LT(huber_error.offset, 0.002);
  EXPECT_LT(huber_error.angle + huber_error.offset, 0.2 * (plain_error.angle + plain_error.offset));
}

TEST(WristLine, TooFewDistinctPointsIsAResult) {
  for (const std::vector<Eigen::Vector2d>& points :
       {std::vector<Eigen::Vector2d>{}, std::vector<Eigen::Vector2d>{{0.1, 0.2}},
        std::vector<Eigen::Vector2d>{{0.1, 0.2}, {0.1, 0.2}, {0.1, 0.2}}}) {
    const WristLineResult r = FitWristLine(points, {});
    EXPECT_EQ(r.termination, WristLineTermination::kInsufficientData);
    EXPECT_FALSE(r.usable());
    EXPECT_THAT(r.message, HasSubstr("two distinct points"));
    EXPECT_THAT(r.BriefReport(), HasSubstr("insufficient data"));
  }
  // two points are enough, and they fix the line.
  const WristLineResult two = FitWristLine({{0.0, 0.0}, {0.0, -1.0}}, {});
  ASSERT_TRUE(two.usable());
  EXPECT_TRUE(testing::MatricesNear(two.line.direction, Eigen::Vector2d(0.0, -1.0), 1e-12));
  EXPECT_NEAR(two.line.offset(), 0.0, 1e-12);
}

TEST(WristLine, OffsetAndAngleConventions) {
  const Line2d line{{2.0, 1.0}, {0.0, 1.0}};  // x = 2, pointing +y
  EXPECT_NEAR(line.angle(), M_PI / 2, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(line.normal(), Eigen::Vector2d(-1.0, 0.0), 0.0));
  EXPECT_NEAR(line.offset(), -2.0, 1e-15);
  EXPECT_NEAR(line.Distance({5.0, -3.0}), 3.0, 1e-15);
  const Line2d reversed{{2.0, 7.0}, {0.0, -1.0}};
  const LineDifference same = CompareLines(line, reversed);  // undirected: the same line
  EXPECT_NEAR(same.angle, 0.0, 1e-15);
  EXPECT_NEAR(same.offset, 0.0, 1e-15);
  const LineDifference d = CompareLines(line, Line2d{{0.0, 0.0}, {1.0, 1.0 / std::sqrt(3.0)}});
  EXPECT_NEAR(d.angle, 60.0 * kDeg, 1e-12);
}

TEST(WristLine, OptionsValidity) {
  WristLineOptions o;
  EXPECT_TRUE(o.IsValid(nullptr));
  std::string why;
  o.loss_scale = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THAT(why, HasSubstr("loss_scale"));
  o = {};
  o.max_iterations = 0;
  EXPECT_FALSE(o.IsValid(nullptr));
  o = {};
  o.cgal_offset_tolerance = std::nan("");
  EXPECT_FALSE(o.IsValid(nullptr));
}

TEST(WristLine, PaperTableIGraspPositionsLieNearALine) {
  const WristLineResult r = FitWristLine(PaperGraspPoints(), {});
  ASSERT_TRUE(r.usable());
  EXPECT_TRUE(r.cgal_agrees);
  EXPECT_LT(r.residuals.max, 0.01);  // within a centimetre: the paper's observation
}

TEST(RadialModel, FitsExactRadialDataWithZeroResidual) {
  const double d = 0.3;
  const double c = -116.0 * kDeg;
  std::vector<double> theta;
  std::vector<Eigen::Vector2d> points;
  for (double t = 20.0; t <= 100.0; t += 10.0) {
    theta.push_back(t * kDeg);
    points.push_back(d * Eigen::Vector2d(std::cos(t * kDeg + c), std::sin(t * kDeg + c)));
  }
  const RadialModelResult r = FitRadialModel(theta, points);
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.d, d, 1e-15);
  EXPECT_NEAR(r.c, c, 1e-14);
  EXPECT_LT(r.residuals.max, 1e-15);
  EXPECT_LT(r.residuals.rms, 1e-15);
  ASSERT_EQ(r.residuals.per_point.size(), points.size());
}

TEST(RadialModel, IsTheLeastSquaresSolution) {
  const std::vector<double> theta = PaperTheta();
  const std::vector<Eigen::Vector2d> points = PaperGraspPoints();
  const RadialModelResult r = FitRadialModel(theta, points);
  ASSERT_TRUE(r.valid);
  const auto cost = [&](double d, double c) {
    double sum = 0.0;
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d model(d * std::cos(theta[i] + c), d * std::sin(theta[i] + c));
      sum += (points[i] - model).squaredNorm();
    }
    return sum;
  };
  const double best = cost(r.d, r.c);
  EXPECT_NEAR(best, r.residuals.rms * r.residuals.rms * points.size(), 1e-15);
  for (double dd : {-1e-4, 1e-4}) EXPECT_GT(cost(r.d + dd, r.c), best);
  for (double dc : {-1e-4, 1e-4}) EXPECT_GT(cost(r.d, r.c + dc), best);
  // on the paper's data the line explains the grasp positions far better than the radial model.
  const WristLineResult line = FitWristLine(points, {});
  EXPECT_GT(r.residuals.rms, 5.0 * line.residuals.rms);
}

TEST(RadialModel, NoPointsIsInvalid) {
  const RadialModelResult r = FitRadialModel({}, {});
  EXPECT_FALSE(r.valid);
}

TEST(WristLine, AngularRangesOfThePaper) {
  const AngularRanges ranges = ComputeAngularRanges(PaperTheta(), PaperGraspPoints());
  EXPECT_NEAR(ranges.object_theta, 80.0 * kDeg, 1e-12);
  EXPECT_NEAR(ranges.position_eta, 34.7 * kDeg, 1e-12);  // -40.6 - (-75.3)
  // a set straddling +-180 deg is measured across it, not around.
  const AngularRanges wrapped =
      ComputeAngularRanges({0.0, 0.1}, {Polar(0.3, 170.0), Polar(0.3, -170.0)});
  EXPECT_NEAR(wrapped.position_eta, 20.0 * kDeg, 1e-12);
  const AngularRanges empty = ComputeAngularRanges({}, {});
  EXPECT_EQ(empty.position_eta, 0.0);
  EXPECT_EQ(empty.object_theta, 0.0);
}

}  // namespace
}  // namespace graspsynth
