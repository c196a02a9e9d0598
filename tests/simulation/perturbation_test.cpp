#include "simulation/perturbation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/errors.hpp"
#include "simulation/random.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::ExampleTrajectory;

const RobotModel& Robot() { return testing::ShippedSimulationModel().robot(); }

Eigen::Isometry3d Wrist(const Vector7d& q) { return ArmFlangePose(Robot().arm, q) * Robot().X_FH; }

TEST(SplitMix64, IsReproducibleAndRoughlyNormal) {
  SplitMix64 a = SplitMix64::ForStream(7, 3), b = SplitMix64::ForStream(7, 3);
  SplitMix64 c = SplitMix64::ForStream(7, 4);
  EXPECT_EQ(a.Next(), b.Next());
  EXPECT_NE(a.Next(), c.Next());
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double x = a.Normal();
    sum += x;
    sum2 += x * x;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.03);
  EXPECT_NEAR(sum2 / n, 1.0, 0.05);
}

TEST(PerturbTrajectory, WithoutNoiseReproducesTheNominal) {
  PerturbationOptions o;
  o.time_scale_min = o.time_scale_max = 1.0;
  o.position_sigma = o.orientation_sigma = o.finger_sigma = 0.0;
  SplitMix64 rng(1);
  const PerturbedTrajectory p = PerturbTrajectory(Robot(), ExampleTrajectory(), o, rng);
  ASSERT_TRUE(p.ok) << p.message;
  ASSERT_EQ(p.trajectory.samples.size(), ExampleTrajectory().samples.size());
  for (size_t i = 0; i < p.trajectory.samples.size(); ++i) {
    const TrajectorySample& a = p.trajectory.samples[i];
    const TrajectorySample& b = ExampleTrajectory().samples[i];
    EXPECT_EQ(a.t, b.t);
    EXPECT_TRUE(testing::MatricesNear(a.arm, b.arm, 1e-8)) << i;
    // the file's 1e-10 rounding may put a value at a joint limit just outside it: clamped.
    EXPECT_TRUE(testing::MatricesNear(a.hand, b.hand, 1e-9)) << i;
  }
}

TEST(PerturbTrajectory, ScalesTimeAndMovesTheWristByTheDrawnNoise) {
  PerturbationOptions o;
  for (uint64_t index = 0; index < 8; ++index) {
    SplitMix64 rng = SplitMix64::ForStream(5, index);
    const PerturbedTrajectory p = PerturbTrajectory(Robot(), ExampleTrajectory(), o, rng);
    ASSERT_TRUE(p.ok) << p.message;
    EXPECT_GE(p.time_scale, 0.7);
    EXPECT_LE(p.time_scale, 1.3);
    EXPECT_NEAR(p.trajectory.duration(), p.time_scale * ExampleTrajectory().duration(), 1e-12);
    EXPECT_TRUE(Robot().arm.WithinLimits(p.trajectory.samples[100].arm));
    EXPECT_TRUE(Robot().hand.WithinLimits(p.trajectory.samples[100].hand));
    // at every waypoint the perturbed wrist is the perturbed waypoint.
    for (size_t k = 0; k < p.trajectory.waypoints.size(); ++k) {
      const WristWaypoint& w = p.trajectory.waypoints[k];
      const TrajectorySample s = SampleAt(p.trajectory, w.t);
      EXPECT_TRUE(testing::PosesNear(Wrist(s.arm), w.pose(), 1e-8)) << k;
      // a few sigma at most (5 mm per axis).
      EXPECT_LT((w.p_WH - ExampleTrajectory().waypoints[k].p_WH).norm(), 0.035);
    }
  }
}

TEST(PerturbTrajectory, KeepsTheObjectsPlacement) {
  JointTrajectory moved = ExampleTrajectory();
  moved.object_xy = Eigen::Vector2d(-0.27, 0.87);
  SplitMix64 rng(3);
  const PerturbedTrajectory p = PerturbTrajectory(Robot(), moved, PerturbationOptions{}, rng);
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_EQ(p.trajectory.theta_deg, moved.theta_deg);
  ASSERT_TRUE(p.trajectory.object_xy.has_value());
  EXPECT_EQ(*p.trajectory.object_xy, *moved.object_xy);
}

TEST(PerturbTrajectory, TheSameStreamGivesTheSameReplay) {
  const PerturbationOptions o;
  SplitMix64 a = SplitMix64::ForStream(11, 2), b = SplitMix64::ForStream(11, 2);
  SplitMix64 c = SplitMix64::ForStream(11, 3);
  const PerturbedTrajectory pa = PerturbTrajectory(Robot(), ExampleTrajectory(), o, a);
  const PerturbedTrajectory pb = PerturbTrajectory(Robot(), ExampleTrajectory(), o, b);
  const PerturbedTrajectory pc = PerturbTrajectory(Robot(), ExampleTrajectory(), o, c);
  EXPECT_EQ(pa.time_scale, pb.time_scale);
  EXPECT_NE(pa.time_scale, pc.time_scale);
  for (size_t i = 0; i < pa.trajectory.samples.size(); ++i) {
    EXPECT_EQ(pa.trajectory.samples[i].arm, pb.trajectory.samples[i].arm);
    EXPECT_EQ(pa.trajectory.samples[i].hand, pb.trajectory.samples[i].hand);
  }
}

TEST(PerturbTrajectory, NoiseHasTheRequestedSpreadAndIsSmooth) {
  // without waypoints the knots are evenly spaced: check the offsets at the knots.
  JointTrajectory t = ExampleTrajectory();
  t.waypoints.clear();
  PerturbationOptions o;
  o.time_scale_min = o.time_scale_max = 1.0;
  o.knot_interval = 0.5;
  double sum2 = 0.0, finger2 = 0.0, worst_step = 0.0;
  int count = 0, finger_count = 0;
  for (int index = 0; index < testing::Scaled(60, 15); ++index) {
    SplitMix64 rng = SplitMix64::ForStream(3, static_cast<uint64_t>(index));
    const PerturbedTrajectory p = PerturbTrajectory(Robot(), t, o, rng);
    ASSERT_TRUE(p.ok);
    for (size_t i = 0; i < t.samples.size(); ++i) {
      const Eigen::Vector3d d =
          Wrist(p.trajectory.samples[i].arm).translation() - Wrist(t.samples[i].arm).translation();
      if (i % 25 == 0) {  // a knot every 0.5 s = 25 samples
        sum2 += d.squaredNorm();
        count += 3;
        // the middle finger's j1 (f7) stays well inside its range: unclamped noise.
        const double df = p.trajectory.samples[i].hand[7] - t.samples[i].hand[7];
        finger2 += df * df;
        ++finger_count;
      }
      if (i > 0) {
        const Eigen::Vector3d d0 = Wrist(p.trajectory.samples[i - 1].arm).translation() -
                                   Wrist(t.samples[i - 1].arm).translation();
        worst_step = std::max(worst_step, (d - d0).norm());
      }
    }
  }
  EXPECT_NEAR(std::sqrt(sum2 / count), o.position_sigma, 0.25 * o.position_sigma);
  EXPECT_NEAR(std::sqrt(finger2 / finger_count), o.finger_sigma, 0.3 * o.finger_sigma);
  // 20 ms between samples, 0.5 s between knots: the offset changes by a few percent of its
  // size per sample, never in jumps.
  EXPECT_LT(worst_step, 0.003);
}

TEST(PerturbTrajectory, AnUnreachablePerturbationIsAResult) {
  PerturbationOptions o;
  o.position_sigma = 2.0;  // metres: far out of reach
  SplitMix64 rng(1);
  const PerturbedTrajectory p = PerturbTrajectory(Robot(), ExampleTrajectory(), o, rng);
  EXPECT_FALSE(p.ok);
  EXPECT_NE(p.message.find("no IK solution"), std::string::npos) << p.message;
}

TEST(PerturbTrajectory, RejectsInvalidOptions) {
  PerturbationOptions o;
  o.time_scale_min = 1.5;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  SplitMix64 rng(1);
  GS_EXPECT_THROW_WITH(PerturbTrajectory(Robot(), ExampleTrajectory(), o, rng), InputError,
                       "time scale");
}

}  // namespace
}  // namespace graspsynth
