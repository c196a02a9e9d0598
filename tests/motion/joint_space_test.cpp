#include "motion/joint_space.hpp"

#include <gtest/gtest.h>

#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}

Eigen::Isometry3d WristPose(const Vector7d& q) {
  return ArmFlangePose(Robot().arm, q) * Robot().X_FH;
}

MotionWaypoint FromPose(const Eigen::Isometry3d& X_WH, double t, const HandVector& f) {
  MotionWaypoint w;
  w.t = t;
  w.p_WH = X_WH.translation();
  w.q_WH = Eigen::Quaterniond(X_WH.linear());
  w.f = f;
  return w;
}

Vector7d Rest() {
  Vector7d q;
  q << 1.8, 0.4, 0.0, 1.6, 0.0, 1.0, 0.0;
  return q;
}

// a palm-down wrist pose above the table in front of the robot (a grasp-like target).
Eigen::Isometry3d PalmDownTarget() {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  Eigen::Matrix3d R;
  R.col(0) = -Eigen::Vector3d::UnitZ();
  R.col(2) = Eigen::Vector3d(0.6, -0.8, 0.0);
  R.col(1) = R.col(2).cross(R.col(0));
  X.linear() = R;
  X.translation() = Eigen::Vector3d(-0.15, 0.55, 0.10);
  return X;
}

CartesianPath ReachPath(double duration) {
  SplineReachOptions options;
  options.duration = duration;
  return SplineReach(FromPose(WristPose(Rest()), 0.0, HandVector::Zero()),
                     FromPose(PalmDownTarget(), 0.0, HandVector::Constant(0.3)),
                     Eigen::Vector3d::Zero(), options);
}

TEST(ToJointTrajectory, ReproducesThePathWithinLimitsAndWithoutJumps) {
  const CartesianPath path = ReachPath(3.0);
  const JointSpaceResult r = ToJointTrajectory(Robot(), path, Rest());
  ASSERT_EQ(r.status, JointSpaceStatus::kOk) << r.message;
  ASSERT_EQ(r.trajectory.samples.size(), path.size());
  EXPECT_EQ(r.trajectory.theta_deg, 0.0);  // the object is the caller's to name
  EXPECT_LT(r.max_joint_step, 0.1);
  for (size_t k = 0; k < path.size(); ++k) {
    const TrajectorySample& s = r.trajectory.samples[k];
    EXPECT_TRUE(Robot().arm.WithinLimits(s.arm));
    const Eigen::Isometry3d X = WristPose(s.arm);
    EXPECT_LT((X.translation() - path[k].p_WH).norm(), 1e-9);
    EXPECT_LT(AngleBetween(Eigen::Quaterniond(X.linear()), path[k].q_WH), 1e-9);
    EXPECT_TRUE(testing::MatricesNear(s.hand, path[k].f, 0.0));
    // the branch of the start never changes.
    EXPECT_EQ(BranchOf(s.arm), BranchOf(Rest()));
  }
}

TEST(ToJointTrajectory, RetimesToRespectTheVelocityCaps) {
  const CartesianPath path = ReachPath(0.3);  // far too fast for S1 and S2 (1 rad/s)
  JointSpaceOptions options;
  const JointSpaceResult r = ToJointTrajectory(Robot(), path, Rest(), options);
  ASSERT_EQ(r.status, JointSpaceStatus::kOk) << r.message;
  EXPECT_GT(r.retimed_segments, 0);
  EXPECT_GT(r.added_time, 0.0);
  const auto& s = r.trajectory.samples;
  for (size_t k = 1; k < s.size(); ++k) {
    const double dt = s[k].t - s[k - 1].t;
    ASSERT_GT(dt, 0.0);
    const Vector7d speed = (s[k].arm - s[k - 1].arm).cwiseAbs() / dt;
    EXPECT_TRUE((speed.array() <= Robot().arm.max_velocity().array() * (0.9 + 1e-9)).all())
        << "segment " << k << ": " << speed.transpose();
  }
  EXPECT_NEAR(s.back().t, 0.3 + r.added_time, 1e-9);
  // without re-timing the same path is too fast.
  options.retime = false;
  const JointSpaceResult fast = ToJointTrajectory(Robot(), path, Rest(), options);
  ASSERT_EQ(fast.status, JointSpaceStatus::kOk);
  EXPECT_EQ(fast.added_time, 0.0);
}

TEST(ToJointTrajectory, ReportsAnUnreachablePose) {
  CartesianPath path = ReachPath(2.0);
  path[40].p_WH = Eigen::Vector3d(2.0, 0.0, 0.5);  // 2 m away: out of reach
  const JointSpaceResult r = ToJointTrajectory(Robot(), path, Rest());
  EXPECT_EQ(r.status, JointSpaceStatus::kUnreachable);
  EXPECT_EQ(r.failed_sample, 40);
  EXPECT_EQ(r.trajectory.samples.size(), 40u);
  EXPECT_NE(r.message.find("wrist pose 40"), std::string::npos);
}

TEST(ToJointTrajectory, ReportsAJump) {
  CartesianPath path = ReachPath(2.0);
  // a half turn of the wrist between two samples.
  path[50].q_WH =
      path[50].q_WH * Eigen::Quaterniond(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()));
  const JointSpaceResult r = ToJointTrajectory(Robot(), path, Rest());
  EXPECT_EQ(r.status, JointSpaceStatus::kJump);
  EXPECT_EQ(r.failed_sample, 50);
}

TEST(SolveWristPose, KeepsAFeasibleArmAngleAndMovesAnInfeasibleOne) {
  const Vector7d q = Rest();
  const double psi = ArmAngleOf(Robot().arm, q);
  const auto same = SolveWristPose(Robot(), WristPose(q), BranchOf(q), psi, q);
  ASSERT_TRUE(same);
  EXPECT_TRUE(testing::MatricesNear(*same, q, 1e-9));
  // at the palm-down target, find an infeasible psi and check the answer moved inside.
  const Eigen::Isometry3d X_WF = PalmDownTarget() * Robot().X_FH.inverse();
  const ArmBranch b = BranchOf(q);
  const std::vector<Interval> feasible =
      FeasibleArmAngles(Robot().arm, PrepareArmTarget(Robot().arm, X_WF, b.gc4), b.gc2, b.gc6);
  ASSERT_FALSE(feasible.empty());
  double outside = 0.0;
  bool found = false;
  for (double p = -M_PI; p < M_PI && !found; p += 0.01) {
    bool in = false;
    for (const Interval& iv : feasible) in |= iv.Contains(p);
    if (!in) {
      outside = p;
      found = true;
    }
  }
  ASSERT_TRUE(found);
  const auto moved = SolveWristPose(Robot(), PalmDownTarget(), b, outside, q);
  ASSERT_TRUE(moved);
  EXPECT_TRUE(Robot().arm.WithinLimits(*moved));
  EXPECT_LT((WristPose(*moved).translation() - PalmDownTarget().translation()).norm(), 1e-9);
}

TEST(JointReach, StartsAndEndsExactlyOnTheMinimumJerkProfile) {
  const Vector7d q0 = Rest();
  Vector7d q1 = q0;
  q1[0] -= 0.4;
  q1[3] += 0.3;
  const HandVector f0 = HandVector::Zero(), f1 = HandVector::Constant(0.2);
  const std::vector<TrajectorySample> s = JointReach(Robot(), q0, f0, q1, f1);
  ASSERT_GE(s.size(), 3u);
  EXPECT_EQ(s.front().t, 0.0);
  EXPECT_EQ(s.front().arm, q0);
  EXPECT_EQ(s.back().arm, q1);
  EXPECT_EQ(s.back().hand, f1);
  EXPECT_NEAR(s.back().t, 2.0, 1e-12);  // small moves keep the minimum duration
  for (size_t k = 1; k < s.size(); ++k) {
    ASSERT_GT(s[k].t, s[k - 1].t);
    // every joint is at the same fraction of its way: a straight line in joint space.
    const double u = (s[k].arm[0] - q0[0]) / (q1[0] - q0[0]);
    EXPECT_NEAR(u, MinimumJerk(s[k].t / 2.0), 1e-12);
    EXPECT_NEAR((s[k].arm[3] - q0[3]) / (q1[3] - q0[3]), u, 1e-12);
    EXPECT_NEAR((s[k].hand[5] - f0[5]) / (f1[5] - f0[5]), u, 1e-12);
  }
}

TEST(JointReach, StretchesALargeMoveToTheVelocityCaps) {
  const Vector7d q0 = Rest();
  Vector7d q1 = q0;
  q1[0] = Robot().arm.lower()[0] + 0.1;  // most of S1's range
  JointReachOptions options;
  options.velocity_scale = 0.5;
  const std::vector<TrajectorySample> s =
      JointReach(Robot(), q0, HandVector::Zero(), q1, HandVector::Zero(), options);
  const double cap = options.velocity_scale * Robot().arm.max_velocity()[0];
  EXPECT_GT(s.back().t, options.min_duration);
  double peak = 0.0;
  for (size_t k = 1; k < s.size(); ++k) {
    peak = std::max(peak, std::abs(s[k].arm[0] - s[k - 1].arm[0]) / (s[k].t - s[k - 1].t));
    for (int j = 0; j < kArmDof; ++j) {
      EXPECT_GE(s[k].arm[j], Robot().arm.lower()[j]);
      EXPECT_LE(s[k].arm[j], Robot().arm.upper()[j]);
    }
  }
  EXPECT_LE(peak, cap * (1.0 + 1e-9));
  EXPECT_GT(peak, 0.95 * cap);  // and not slower than needed
}

}  // namespace
}  // namespace graspsynth
