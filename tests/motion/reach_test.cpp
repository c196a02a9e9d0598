#include "motion/reach.hpp"

#include <gtest/gtest.h>

#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

using testing::MatricesNear;

MotionWaypoint Pose(const Eigen::Vector3d& p, double yaw, double closure, double t = 0.0) {
  MotionWaypoint w;
  w.t = t;
  w.p_WH = p;
  w.q_WH = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  w.f = HandVector::Constant(closure);
  return w;
}

TEST(SplineReach, StartsAtRestAndArrivesAtThePregraspWithItsVelocity) {
  const MotionWaypoint start = Pose({0.3, 0.4, 0.6}, 0.0, 0.0, 5.0);
  const MotionWaypoint pre = Pose({-0.1, 0.6, 0.2}, 1.2, 0.3);
  const Eigen::Vector3d v_end(0.0, 0.05, -0.1);
  SplineReachOptions options;
  options.duration = 2.0;
  options.sample_period = 0.001;
  const CartesianPath path = SplineReach(start, pre, v_end, options);
  ASSERT_EQ(path.size(), 2001u);
  EXPECT_NEAR(path.front().t, 5.0, 1e-12);
  EXPECT_NEAR(path.back().t, 7.0, 1e-12);
  EXPECT_TRUE(MatricesNear(path.front().p_WH, start.p_WH, 1e-12));
  EXPECT_TRUE(MatricesNear(path.back().p_WH, pre.p_WH, 0.0));
  EXPECT_LT(AngleBetween(path.back().q_WH, pre.q_WH), 1e-15);
  EXPECT_TRUE(MatricesNear(path.back().f, pre.f, 0.0));
  // clamped ends: zero start velocity, v_end at the pre-grasp (one-sided difference error).
  EXPECT_LT(((path[1].p_WH - path[0].p_WH) / 0.001).norm(), 1e-3);
  EXPECT_TRUE(MatricesNear(((path[2000].p_WH - path[1999].p_WH) / 0.001).eval(), v_end, 2e-3));
  // a smooth path: no jump between samples, orientation on the shorter arc at constant axis.
  for (size_t k = 1; k < path.size(); ++k) {
    EXPECT_LT((path[k].p_WH - path[k - 1].p_WH).norm(), 1e-3);
    EXPECT_GT(path[k].t, path[k - 1].t);
  }
  EXPECT_NEAR(AngleBetween(path[1000].q_WH, start.q_WH), 0.6, 1e-9);  // 3u^2-2u^3 at 1/2
}

TEST(SplineReach, PassesThroughViaPoints) {
  const MotionWaypoint start = Pose({0.3, 0.4, 0.6}, 0.0, 0.0);
  const MotionWaypoint pre = Pose({-0.1, 0.6, 0.2}, 0.5, 0.3);
  SplineReachOptions options;
  options.duration = 1.0;
  options.sample_period = 1e-4;
  options.via_points = {Eigen::Vector3d(0.1, 0.5, 0.5)};
  const CartesianPath path = SplineReach(start, pre, Eigen::Vector3d::Zero(), options);
  double closest = 1.0;
  for (const MotionWaypoint& w : path) {
    closest = std::min(closest, (w.p_WH - options.via_points[0]).norm());
  }
  EXPECT_LT(closest, 1e-4);
}

TEST(SplineReachOptions, RejectsBadValues) {
  SplineReachOptions o;
  o.duration = 0.0;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "SplineReachOptions::duration must be positive");
}

TEST(PositionDmp, ReproducesItsDemonstrationAndGeneralizes) {
  // a curved demonstration: a lift in z on the way to the goal.
  std::vector<double> times;
  std::vector<Eigen::Vector3d> demo;
  for (int k = 0; k <= 200; ++k) {
    const double u = k / 200.0;
    const double s = u * u * u * (10 - 15 * u + 6 * u * u);
    times.push_back(2.0 * u);
    demo.emplace_back(0.4 * s, 0.2 * s, 0.15 * std::sin(M_PI * s));
  }
  DmpReachOptions options;
  options.sample_period = 0.01;
  const PositionDmp dmp(times, demo, options);
  const std::vector<Eigen::Vector3d> same = dmp.Rollout(demo.front(), demo.back());
  ASSERT_EQ(same.size(), 201u);
  double worst = 0.0;
  for (size_t k = 0; k < same.size(); ++k) worst = std::max(worst, (same[k] - demo[k]).norm());
  EXPECT_LT(worst, 0.005);  // 5 mm over a 45 cm path
  // a new goal: ends there, keeps the arch.
  const Eigen::Vector3d goal(0.3, 0.4, 0.05);
  const std::vector<Eigen::Vector3d> moved = dmp.Rollout(Eigen::Vector3d::Zero(), goal);
  EXPECT_LT((moved.back() - goal).norm(), 0.01);
  double top = 0.0;
  for (const auto& p : moved) top = std::max(top, p.z());
  EXPECT_GT(top, 0.12);
}

TEST(DmpReach, EndsExactlyAtThePregrasp) {
  // a demonstrated reach at 60 Hz: minimum-jerk progress with an arch in z.
  std::vector<double> times;
  std::vector<Eigen::Vector3d> demo;
  for (int k = 0; k <= 120; ++k) {
    const double u = k / 120.0;
    const double s = u * u * u * (10 - 15 * u + 6 * u * u);
    times.push_back(2.0 * u);
    demo.emplace_back(0.4 * s, 0.0, 0.08 * std::sin(M_PI * s));
  }
  DmpReachOptions options;
  const PositionDmp dmp(times, demo, options);
  const MotionWaypoint start = Pose({0.3, 0.4, 0.6}, 0.0, 0.0, 1.0);
  const MotionWaypoint pre = Pose({-0.1, 0.6, 0.2}, 1.0, 0.4);
  const CartesianPath path = DmpReach(dmp, start, pre, options);
  EXPECT_NEAR(path.front().t, 1.0, 1e-12);
  EXPECT_NEAR(path.back().t, 3.0, 1e-12);
  EXPECT_TRUE(MatricesNear(path.back().p_WH, pre.p_WH, 0.0));
  EXPECT_LT(AngleBetween(path.back().q_WH, pre.q_WH), 1e-15);
  EXPECT_LT((path[path.size() - 2].p_WH - pre.p_WH).norm(), 0.01);
}

TEST(LiftPath, SettlesRisesAndHolds) {
  const MotionWaypoint grasp = Pose({-0.1, 0.6, 0.1}, 0.3, 0.9, 4.0);
  LiftOptions options;
  const CartesianPath path = LiftPath(grasp, options);
  ASSERT_FALSE(path.empty());
  EXPECT_GT(path.front().t, 4.0);
  EXPECT_NEAR(path.back().t, 4.0 + 0.4 + 1.0 + 1.2, 1e-9);
  for (const MotionWaypoint& w : path) {
    EXPECT_NEAR(w.p_WH.x(), grasp.p_WH.x(), 0.0);
    EXPECT_LT(AngleBetween(w.q_WH, grasp.q_WH), 1e-15);
    EXPECT_TRUE(MatricesNear(w.f, grasp.f, 0.0));
    const double rel = w.t - 4.0;
    if (rel <= 0.4) {
      EXPECT_NEAR(w.p_WH.z(), 0.1, 1e-15);
    } else if (rel >= 1.4) {
      EXPECT_NEAR(w.p_WH.z(), 0.2, 1e-12);
    }
  }
}

}  // namespace
}  // namespace graspsynth
