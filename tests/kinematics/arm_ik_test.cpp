#include "kinematics/arm_ik.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Deg;
using testing::NearSingular;
using testing::PoseError;
using testing::PosesNear;
using testing::RandomConfiguration;

// FK(IK(x)) must reproduce x to this, in metres and rotation-matrix entries.
constexpr double kPoseTol = 1e-9;
double RandomPsi(std::mt19937_64* rng) {
  return std::uniform_real_distribution<double>(-M_PI, M_PI)(*rng);
}

// |a - b| modulo 2*pi.
double AngleDistance(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * M_PI)); }

double MaxAngleDistance(const Vector7d& a, const Vector7d& b) {
  double worst = 0.0;
  for (int i = 0; i < kArmDof; ++i) worst = std::max(worst, AngleDistance(a[i], b[i]));
  return worst;
}

bool AllFinite(const Vector7d& q) { return q.allFinite(); }

// The branch's joints at psi are within limits (some 2*pi-equivalent of each joint is): the
// brute-force definition that FeasibleArmAngles must reproduce.
bool FeasibleByEvaluation(const ArmModel& arm, const ArmTargetForm& form, double psi, int gc2,
                          int gc6) {
  const Vector7d q = JointsAtArmAngle(form, psi, gc2, gc6);
  return NearestEquivalent(arm, q, Vector7d::Zero()).has_value();
}

TEST(ArmIk, ForwardOfInverseReproducesThePoseOnEveryBranch) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(20240611);
  constexpr int kConfigurations = 100000;
  double worst = 0.0;
  int64_t checked = 0, failures = 0, wrong_branch = 0, bad_status = 0, not_finite = 0;
  int used = 0;
  while (used < kConfigurations) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    ++used;
    const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
    // the configuration's own arm angle on every other draw, a random one in between (where
    // other branches are often off limits and near their singular points).
    const double psi = used % 2 == 0 ? ArmAngleOf(arm, q) : RandomPsi(&rng);
    for (int index = 0; index < 8; ++index) {
      const ArmBranch branch = ArmBranch::FromIndex(index);
      const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, branch);
      // |E1| <= 137 deg and the limits are symmetric: both elbow signs are solvable.
      if (s.status != IkStatus::kOk && s.status != IkStatus::kOutOfLimits) {
        ++bad_status;
        continue;
      }
      if (!AllFinite(s.q)) {
        ++not_finite;
        continue;
      }
      if (s.status == IkStatus::kOk && !arm.WithinLimits(s.q)) ++failures;
      if (NearSingular(s.q)) continue;
      if (!(BranchOf(s.q) == branch)) ++wrong_branch;
      const double err = PoseError(ArmFlangePose(arm, s.q), X_WF);
      worst = std::max(worst, err);
      if (!(err <= kPoseTol)) ++failures;
      ++checked;
    }
  }
  std::cout << "[   info   ] FK(IK) checked " << checked << " solutions, worst error " << worst
            << "\n";
  EXPECT_EQ(bad_status, 0);
  EXPECT_EQ(not_finite, 0);
  EXPECT_EQ(wrong_branch, 0);
  EXPECT_EQ(failures, 0) << "worst pose error " << worst;
  EXPECT_LE(worst, kPoseTol);
  EXPECT_GT(checked, 7 * kConfigurations);  // most solutions are regular
}

TEST(ArmIk, JointsAtArmAngleStayInTheHalfOpenCircle) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(7);
  for (int k = 0; k < 2000; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    const ArmTargetForm form = PrepareArmTarget(arm, ArmFlangePose(arm, q), BranchOf(q).gc4);
    ASSERT_EQ(form.status, IkStatus::kOk);
    EXPECT_NEAR(form.theta4, q[3], 1e-12) << "E1 is fixed by the target";
    for (const double psi : {RandomPsi(&rng), -M_PI, M_PI, 0.0}) {
      for (const int gc2 : {1, -1}) {
        for (const int gc6 : {1, -1}) {
          const Vector7d v = JointsAtArmAngle(form, psi, gc2, gc6);
          ASSERT_TRUE(AllFinite(v));
          EXPECT_TRUE((v.array() > -M_PI).all() && (v.array() <= M_PI).all()) << v.transpose();
          EXPECT_GE(v[1] * gc2, 0.0);
          EXPECT_GE(v[5] * gc6, 0.0);
        }
      }
    }
  }
}

TEST(ArmAngle, RoundTripReturnsTheConfiguration) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(3);
  double worst = 0.0;
  int used = 0;
  while (used < 20000) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    ++used;
    const double psi = ArmAngleOf(arm, q);
    ASSERT_TRUE(psi > -M_PI && psi <= M_PI);
    const ArmIkSolution s = SolveArmIk(arm, ArmFlangePose(arm, q), psi, BranchOf(q), &q);
    ASSERT_EQ(s.status, IkStatus::kOk) << q.transpose();
    // q_near = q picks the same 2*pi-equivalents, so the joints compare directly.
    const double err = (s.q - q).cwiseAbs().maxCoeff();
    worst = std::max(worst, err);
    ASSERT_LE(err, 1e-9) << "q = " << q.transpose() << "\nIK = " << s.q.transpose();
  }
  std::cout << "[   info   ] psi round trip worst joint error " << worst << " rad\n";
}

TEST(ArmAngle, IsZeroForTheReferencePlaneAndForAStretchedArm) {
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q;
  q << 0.4, 0.6, 0.0, 1.1, 0.3, -0.7, 0.2;
  EXPECT_NEAR(ArmAngleOf(arm, q), 0.0, 1e-12) << "S3 = 0 is the reference plane";
  q[2] = 0.5;
  EXPECT_GT(std::abs(ArmAngleOf(arm, q)), 0.1);
  q[3] = 0.0;
  EXPECT_EQ(ArmAngleOf(arm, q), 0.0) << "stretched: the angle is undefined and reported as 0";
}

TEST(ArmAngle, WristCentreOnTheBaseAxisUsesZeroReferenceAzimuth) {
  const ArmModel arm = testing::Pa10FromDh();
  const SrsLengths& len = arm.lengths();
  std::mt19937_64 rng(11);
  for (int k = 0; k < 200; ++k) {
    // any orientation, wrist centre exactly on the base z axis, 0.7 m above the shoulder.
    const Eigen::Matrix3d R = ArmFlangePose(arm, RandomConfiguration(arm, &rng)).linear();
    Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
    X_WF.linear() = R;
    X_WF.translation() = Eigen::Vector3d(0.0, 0.0, len.d_bs + 0.7) + len.d_wt * R.col(2);
    for (const int gc4 : {1, -1}) {
      const ArmTargetForm form = PrepareArmTarget(arm, X_WF, gc4);
      ASSERT_EQ(form.status, IkStatus::kOk);
      // the reference plane (S1 = 0, S3 = 0) is the psi = 0 solution of the branch whose S2
      // leans against the elbow.
      const Vector7d q0 = JointsAtArmAngle(form, 0.0, -gc4, 1);
      EXPECT_NEAR(q0[0], 0.0, 1e-12);
      EXPECT_NEAR(q0[2], 0.0, 1e-12);
      for (int index = 0; index < 8; ++index) {
        const ArmBranch branch = ArmBranch::FromIndex(index);
        if (branch.gc4 != gc4) continue;
        const double psi = RandomPsi(&rng);
        const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, branch);
        ASSERT_TRUE(s.status == IkStatus::kOk || s.status == IkStatus::kOutOfLimits);
        if (NearSingular(s.q)) continue;
        EXPECT_TRUE(PosesNear(ArmFlangePose(arm, s.q), X_WF, kPoseTol));
        // psi turns the elbow about the (vertical) shoulder-wrist axis from azimuth 0.
        if (branch.gc2 == -gc4) {
          EXPECT_LE(AngleDistance(s.q[0], psi), 1e-9);
        }
      }
    }
  }
}

// Counts of the special cases met by the scan comparison, to show they were exercised.
struct ScanStats {
  int64_t samples = 0;
  int64_t mismatches = 0;
  int64_t wrapping = 0;
  int64_t empty = 0;
  int64_t full = 0;
  int64_t sets = 0;
};

// Compares FeasibleArmAngles with a dense scan for every branch of a target.
void CompareWithScan(const ArmModel& arm, const Eigen::Isometry3d& X_WF, ScanStats* stats) {
  constexpr int kSamples = 3600;
  constexpr double kBoundaryBand = 1e-6;
  for (int index = 0; index < 8; ++index) {
    const ArmBranch b = ArmBranch::FromIndex(index);
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
    const std::vector<Interval> set = FeasibleArmAngles(arm, form, b.gc2, b.gc6);
    if (form.status != IkStatus::kOk) {
      EXPECT_TRUE(set.empty());
      continue;
    }
    ++stats->sets;
    // sorted, disjoint, inside [-pi, pi], and not split where nothing changes.
    for (size_t i = 0; i < set.size(); ++i) {
      EXPECT_LT(set[i].lo, set[i].hi);
      EXPECT_GE(set[i].lo, -M_PI);
      EXPECT_LE(set[i].hi, M_PI);
      if (i > 0) {
        EXPECT_LT(set[i - 1].hi, set[i].lo);
      }
    }
    if (set.empty()) ++stats->empty;
    if (set.size() == 1 && set[0].lo == -M_PI && set[0].hi == M_PI) ++stats->full;
    if (set.size() >= 2 && set.front().lo == -M_PI && set.back().hi == M_PI) ++stats->wrapping;
    for (int k = 0; k < kSamples; ++k) {
      const double psi = -M_PI + (k + 0.5) * 2.0 * M_PI / kSamples;
      const bool expected = FeasibleByEvaluation(arm, form, psi, b.gc2, b.gc6);
      bool inside = false;
      double boundary_distance = 1e9;
      for (const Interval& iv : set) {
        inside = inside || iv.Contains(psi);
        boundary_distance =
            std::min({boundary_distance, std::abs(psi - iv.lo), std::abs(psi - iv.hi)});
      }
      ++stats->samples;
      if (inside != expected && boundary_distance > kBoundaryBand) {
        if (stats->mismatches < 5) {
          ADD_FAILURE() << "branch " << index << " psi " << psi << " scan says " << expected;
        }
        ++stats->mismatches;
      }
    }
  }
}

TEST(FeasibleArmAngles, AgreeWithADenseScan) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(5);
  ScanStats stats;
  for (int k = 0; k < 1000; ++k) {
    Vector7d q = RandomConfiguration(arm, &rng);
    // every fourth target comes from S2 and W1 beyond their limits: many empty sets.
    const bool in_limits = k % 4 != 0;
    if (!in_limits) {
      for (const int j : {1, 5}) q[j] = std::uniform_real_distribution<double>(-3.1, 3.1)(rng);
    }
    const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
    CompareWithScan(arm, X_WF, &stats);
    // an in-limit configuration's own arm angle lies in its branch's set.
    if (in_limits && !NearSingular(q)) {
      const ArmBranch b = BranchOf(q);
      const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
      const double psi = ArmAngleOf(arm, q);
      bool found = false;
      for (const Interval& iv : FeasibleArmAngles(arm, form, b.gc2, b.gc6)) {
        found = found || (iv.lo - 1e-9 <= psi && psi <= iv.hi + 1e-9);
      }
      EXPECT_TRUE(found) << "psi " << psi << " of q = " << q.transpose();
    }
  }
  std::cout << "[   info   ] feasible psi: " << stats.sets << " sets, " << stats.samples
            << " samples, " << stats.mismatches << " mismatches; " << stats.wrapping
            << " wrap through pi, " << stats.empty << " empty, " << stats.full << " full\n";
  EXPECT_EQ(stats.mismatches, 0);
  EXPECT_GT(stats.wrapping, 100);
  EXPECT_GT(stats.empty, 100);
}

TEST(FeasibleArmAngles, AgreeWithADenseScanAtDegenerateTargets) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(17);
  ScanStats stats;
  for (int k = 0; k < 300; ++k) {
    Vector7d q = RandomConfiguration(arm, &rng);
    switch (k % 3) {
      case 0:
        q[1] = 0.0;  // S2 = 0: S1 and S3 jump by pi at one psi
        break;
      case 1:
        q[5] = 0.0;  // W1 = 0: E2 and W2 jump by pi at one psi
        break;
      default: {
        // S1 exactly at its limit at psi = pi: a limit crossing at the seam of the circle
        // (turning the target about the base axis moves S1 alone, not psi).
        const ArmIkSolution s = SolveArmIk(arm, ArmFlangePose(arm, q), M_PI, BranchOf(q), &q);
        ASSERT_TRUE(s.status == IkStatus::kOk || s.status == IkStatus::kOutOfLimits);
        q = s.q;
        q[0] = (k % 2 == 0) ? arm.upper()[0] : arm.lower()[0];
        break;
      }
    }
    CompareWithScan(arm, ArmFlangePose(arm, q), &stats);
  }
  std::cout << "[   info   ] degenerate feasible psi: " << stats.sets << " sets, " << stats.samples
            << " samples, " << stats.mismatches << " mismatches\n";
  EXPECT_EQ(stats.mismatches, 0);
}

TEST(FeasibleArmAngles, AreEmptyWithoutAValidForm) {
  const ArmModel arm = testing::Pa10FromDh();
  Eigen::Isometry3d far = Eigen::Isometry3d::Identity();
  far.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
  const ArmTargetForm form = PrepareArmTarget(arm, far, 1);
  ASSERT_EQ(form.status, IkStatus::kUnreachable);
  EXPECT_TRUE(FeasibleArmAngles(arm, form, 1, 1).empty());
}

TEST(FeasibleArmAngles, WholeCircleWhenNoJointBinds) {
  // an arm whose S1, S3 and W1 turn freely and whose S2 spans both signs: only S2's sign and
  // E1 matter, so a regular target is feasible for every psi on its own branch.
  Vector7d lower = testing::Pa10Lower();
  Vector7d upper = testing::Pa10Upper();
  for (const int j : {0, 2, 5}) {
    lower[j] = -4.0;
    upper[j] = 4.0;
  }
  lower[1] = -M_PI;
  upper[1] = M_PI;
  const ArmModel arm = ArmModel::FromDh({0.317, 0.450, 0.480, 0.070}, lower, upper,
                                        Vector7d::Ones(), Vector7d::Ones());
  Vector7d q;
  q << 0.3, 0.8, -0.5, 1.2, 0.4, 0.9, -0.1;
  const ArmTargetForm form = PrepareArmTarget(arm, ArmFlangePose(arm, q), 1);
  const std::vector<Interval> set = FeasibleArmAngles(arm, form, 1, 1);
  ASSERT_EQ(set.size(), 1u);
  EXPECT_EQ(set[0].lo, -M_PI);
  EXPECT_EQ(set[0].hi, M_PI);
}

TEST(ArmIkAllBranches, ReturnsExactlyTheInLimitBranchSolutions) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(23);
  int64_t solutions = 0;
  int used = 0;
  while (used < 3000) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    ++used;
    const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
    const double psi = ArmAngleOf(arm, q);
    const std::vector<Vector7d> all = SolveArmIkAllBranches(arm, X_WF, psi);
    ASSERT_LE(all.size(), 8u);
    solutions += static_cast<int64_t>(all.size());
    // the same solutions, in branch order, as SolveArmIk branch by branch.
    std::vector<Vector7d> expected;
    for (int index = 0; index < 8; ++index) {
      const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, ArmBranch::FromIndex(index));
      if (s.status == IkStatus::kOk) expected.push_back(s.q);
    }
    ASSERT_EQ(all.size(), expected.size());
    bool has_own = false;
    for (size_t i = 0; i < all.size(); ++i) {
      EXPECT_TRUE(testing::MatricesNear(all[i], expected[i], 0.0));
      EXPECT_TRUE(arm.WithinLimits(all[i]));
      if (!NearSingular(all[i])) {
        EXPECT_TRUE(PosesNear(ArmFlangePose(arm, all[i]), X_WF, kPoseTol));
      }
      if (BranchOf(all[i]) == BranchOf(q)) {
        has_own = true;
        EXPECT_LE(MaxAngleDistance(all[i], q), 1e-9);
      }
    }
    EXPECT_TRUE(has_own) << "q = " << q.transpose();
  }
  EXPECT_GT(solutions, 3000);  // other branches are often in limits too
}

TEST(ArmIkStatus, TargetBeyondReachIsUnreachable) {
  const ArmModel arm = testing::Pa10FromDh();
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
  X_WF.translation() = Eigen::Vector3d(1.2, 0.0, 0.317);
  for (const int gc4 : {1, -1}) {
    EXPECT_EQ(PrepareArmTarget(arm, X_WF, gc4).status, IkStatus::kUnreachable);
  }
  // wrist centre at the shoulder: closer than |d_se - d_ew|.
  X_WF.translation() = Eigen::Vector3d(0.0, 0.0, 0.317 + 0.070);
  EXPECT_EQ(PrepareArmTarget(arm, X_WF, 1).status, IkStatus::kUnreachable);
  const ArmIkSolution s = SolveArmIk(arm, X_WF, 0.3, ArmBranch{});
  EXPECT_EQ(s.status, IkStatus::kUnreachable);
  EXPECT_TRUE(AllFinite(s.q));
  EXPECT_TRUE(SolveArmIkAllBranches(arm, X_WF, 0.3).empty());
  // a non-finite target is unreachable too, not NaN joints.
  X_WF.translation().x() = std::nan("");
  EXPECT_EQ(SolveArmIk(arm, X_WF, 0.0, ArmBranch{}).status, IkStatus::kUnreachable);
}

TEST(ArmIkStatus, StretchedArmIsSingular) {
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q;
  q << 0.2, 0.5, -0.3, 0.0, 0.7, 0.4, 0.1;
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  for (const int gc4 : {1, -1}) {
    EXPECT_EQ(PrepareArmTarget(arm, X_WF, gc4).status, IkStatus::kSingular);
  }
  const ArmIkSolution s = SolveArmIk(arm, X_WF, 0.0, BranchOf(q));
  EXPECT_EQ(s.status, IkStatus::kSingular);
  EXPECT_TRUE(AllFinite(s.q));
  // a slightly bent elbow is regular again and solves exactly.
  q[3] = 2e-3;
  const ArmIkSolution bent =
      SolveArmIk(arm, ArmFlangePose(arm, q), ArmAngleOf(arm, q), BranchOf(q), &q);
  ASSERT_EQ(bent.status, IkStatus::kOk);
  EXPECT_TRUE(testing::MatricesNear(bent.q, q, 1e-9));
}

TEST(ArmIkStatus, ElbowBeyondItsLimitIsElbowLimit) {
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q;
  q << 0.2, 0.5, -0.3, Deg(150), 0.7, 0.4, 0.1;
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  for (const int gc4 : {1, -1}) {
    EXPECT_EQ(PrepareArmTarget(arm, X_WF, gc4).status, IkStatus::kElbowLimit);
  }
  const ArmIkSolution s = SolveArmIk(arm, X_WF, 0.0, BranchOf(q));
  EXPECT_EQ(s.status, IkStatus::kElbowLimit);
  EXPECT_TRUE(AllFinite(s.q));
  // just inside the limit it solves.
  q[3] = Deg(136.9);
  EXPECT_EQ(PrepareArmTarget(arm, ArmFlangePose(arm, q), 1).status, IkStatus::kOk);
}

TEST(ArmIkStatus, OffLimitJointIsOutOfLimitsWithTheClosedFormValue) {
  const ArmModel arm = testing::Pa10FromDh();
  // S1 = 179 deg is beyond +-177 deg; the pose is still solved exactly.
  Vector7d q;
  q << Deg(179), 0.5, -0.3, 1.0, 0.7, 0.4, 0.1;
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  const ArmIkSolution s = SolveArmIk(arm, X_WF, ArmAngleOf(arm, q), BranchOf(q));
  EXPECT_EQ(s.status, IkStatus::kOutOfLimits);
  EXPECT_TRUE(testing::MatricesNear(s.q, q, 1e-9));
  EXPECT_TRUE(PosesNear(ArmFlangePose(arm, s.q), X_WF, kPoseTol));
}

TEST(ArmIkStatus, HasShortNames) {
  EXPECT_EQ(ToString(IkStatus::kOk), "ok");
  EXPECT_EQ(ToString(IkStatus::kUnreachable), "unreachable");
  EXPECT_EQ(ToString(IkStatus::kSingular), "singular");
  EXPECT_EQ(ToString(IkStatus::kElbowLimit), "elbow limit");
  EXPECT_EQ(ToString(IkStatus::kOutOfLimits), "out of limits");
}

TEST(ArmIkWideJoints, PickTheEquivalentNearestTheCurrentConfiguration) {
  const ArmModel arm = testing::Pa10FromDh();
  // E2 = 200 deg is reported by the closed form as -160 deg.
  Vector7d q;
  q << 0.2, 0.5, -0.3, 1.0, Deg(200), 0.4, Deg(-230);
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  const double psi = ArmAngleOf(arm, q);
  const ArmIkSolution near_q = SolveArmIk(arm, X_WF, psi, BranchOf(q), &q);
  ASSERT_EQ(near_q.status, IkStatus::kOk);
  EXPECT_NEAR(near_q.q[4], Deg(200), 1e-9);
  EXPECT_NEAR(near_q.q[6], Deg(-230), 1e-9);
  const ArmIkSolution near_zero = SolveArmIk(arm, X_WF, psi, BranchOf(q));
  ASSERT_EQ(near_zero.status, IkStatus::kOk);
  EXPECT_NEAR(near_zero.q[4], Deg(-160), 1e-9);
  EXPECT_NEAR(near_zero.q[6], Deg(130), 1e-9);
}

TEST(NearestEquivalentAngle, PicksTheInRangeValueClosestToTheReference) {
  const double wide = Deg(255);
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(3.0, 0.0, -wide, wide), 3.0);
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(3.0, -3.0, -wide, wide), 3.0 - 2.0 * M_PI);
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(-3.0, 3.5, -wide, wide), -3.0 + 2.0 * M_PI);
  // the closer equivalent is out of range: the other one is taken.
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(3.0, -3.0, Deg(-177), Deg(177)), 3.0);
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(-2.0, 4.0, Deg(-177), Deg(177)), -2.0);
  // far-off input angles are brought back by several turns.
  EXPECT_NEAR(*NearestEquivalentAngle(10.0, 0.0, -M_PI, M_PI), 10.0 - 4.0 * M_PI, 1e-12);
  EXPECT_NEAR(*NearestEquivalentAngle(-20.0, 1.0, -wide, wide), -20.0 + 6.0 * M_PI, 1e-12);
  // -20 + 4 pi = -7.43 is nearer to -7 but outside +-255 deg.
  EXPECT_NEAR(*NearestEquivalentAngle(-20.0, -7.0, -wide, wide), -20.0 + 6.0 * M_PI, 1e-12);
  // the limits themselves are inside.
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(Deg(177), 0.0, Deg(-177), Deg(177)), Deg(177));
  EXPECT_DOUBLE_EQ(*NearestEquivalentAngle(Deg(-177), 0.0, Deg(-177), Deg(177)), Deg(-177));
  // no equivalent fits.
  EXPECT_FALSE(NearestEquivalentAngle(3.0, 0.0, -1.0, 1.0).has_value());
  EXPECT_FALSE(NearestEquivalentAngle(Deg(179), 0.0, Deg(-177), Deg(177)).has_value());
  EXPECT_FALSE(NearestEquivalentAngle(std::nan(""), 0.0, -wide, wide).has_value());
}

TEST(NearestEquivalent, MapsEveryJointOrFails) {
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q;
  q << 0.1, 0.2, 0.3, 0.4, -3.0, 0.6, 3.0;
  Vector7d ref = Vector7d::Zero();
  ref[4] = 3.0;
  ref[6] = -3.0;
  const std::optional<Vector7d> mapped = NearestEquivalent(arm, q, ref);
  ASSERT_TRUE(mapped.has_value());
  Vector7d expected = q;
  expected[4] = -3.0 + 2.0 * M_PI;
  expected[6] = 3.0 - 2.0 * M_PI;
  EXPECT_TRUE(testing::MatricesNear(*mapped, expected, 1e-15));
  q[3] = Deg(140);  // E1 beyond +-137 deg and no equivalent inside
  EXPECT_FALSE(NearestEquivalent(arm, q, ref).has_value());
}

TEST(ArmBranch, SignsIndexAndBranchOf) {
  for (int index = 0; index < 8; ++index) {
    EXPECT_EQ(ArmBranch::FromIndex(index).index(), index);
  }
  Vector7d q = Vector7d::Zero();
  EXPECT_EQ(BranchOf(q), (ArmBranch{1, 1, 1})) << "zero joints count as +1";
  q << 0.0, -0.2, 0.0, 0.5, 0.0, -0.1, 0.0;
  EXPECT_EQ(BranchOf(q), (ArmBranch{-1, 1, -1}));
  EXPECT_EQ(BranchOf(q).index(), 5);
}

// d(theta)/d(psi) of a tangent-type joint (robot.md 1.5 step 6), whose coefficients the
// feasible-set construction uses to find the singular psi, against finite differences.
TEST(ArmIk, TangentJointDerivativeMatchesFiniteDifferences) {
  const ArmModel arm = testing::Pa10FromDh();
  std::mt19937_64 rng(29);
  double worst = 0.0;
  for (int k = 0; k < 200; ++k) {
    const Vector7d q = RandomConfiguration(arm, &rng);
    if (NearSingular(q)) continue;
    const ArmBranch b = BranchOf(q);
    const ArmTargetForm form = PrepareArmTarget(arm, ArmFlangePose(arm, q), b.gc4);
    ASSERT_EQ(form.status, IkStatus::kOk);
    // S1 = atan2(-gc2 s22, -gc2 s12) with s = As sin + Bs cos + Cs.
    const double g = -b.gc2;
    const double an = g * form.As(1, 1), bn = g * form.Bs(1, 1), cn = g * form.Cs(1, 1);
    const double ad = g * form.As(0, 1), bd = g * form.Bs(0, 1), cd = g * form.Cs(0, 1);
    const double at = bd * cn - bn * cd, bt = an * cd - ad * cn, ct = an * bd - ad * bn;
    const double psi = RandomPsi(&rng);
    const double un = an * std::sin(psi) + bn * std::cos(psi) + cn;
    const double ud = ad * std::sin(psi) + bd * std::cos(psi) + cd;
    if (un * un + ud * ud < 1e-2) continue;  // near the jump the difference quotient is poor
    const double analytic = (at * std::sin(psi) + bt * std::cos(psi) + ct) / (un * un + ud * ud);
    const double h = 1e-6;
    const double numeric = std::remainder(JointsAtArmAngle(form, psi + h, b.gc2, b.gc6)[0] -
                                              JointsAtArmAngle(form, psi - h, b.gc2, b.gc6)[0],
                                          2.0 * M_PI) /
                           (2.0 * h);
    worst = std::max(worst, std::abs(analytic - numeric));
  }
  EXPECT_LE(worst, 1e-6);
}

}  // namespace
}  // namespace graspsynth

namespace graspsynth {
namespace {

TEST(WidestInterval, PicksTheFirstWidest) {
  EXPECT_FALSE(WidestInterval({}));
  const auto w = WidestInterval({{-1.0, -0.5}, {0.0, 1.0}, {2.0, 3.0}});
  ASSERT_TRUE(w);
  EXPECT_EQ(w->lo, 0.0);
}

TEST(SolveArmIkMidArc, SolvesAtTheMiddleOfTheWidestArc) {
  const ArmModel arm = testing::Pa10FromDh();
  Vector7d q;
  q << 0.4, 0.6, -0.3, 1.2, 0.5, -0.9, 0.3;
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  const auto s = SolveArmIkMidArc(arm, X_WF);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->branch.index(), 0);  // elbow-up (+, +, +) is tried first
  EXPECT_TRUE(arm.WithinLimits(s->q));
  EXPECT_TRUE(testing::PosesNear(ArmFlangePose(arm, s->q), X_WF, 1e-9));
  const ArmTargetForm form = PrepareArmTarget(arm, X_WF, +1);
  const auto widest = WidestInterval(FeasibleArmAngles(arm, form, +1, +1));
  ASSERT_TRUE(widest);
  EXPECT_DOUBLE_EQ(s->psi, 0.5 * (widest->lo + widest->hi));
  EXPECT_NEAR(ArmAngleOf(arm, s->q), s->psi, 1e-9);
  // a given branch is the only one tried.
  const ArmBranch other{1, 1, -1};
  const auto t = SolveArmIkMidArc(arm, X_WF, other);
  ASSERT_TRUE(t);
  EXPECT_EQ(t->branch, other);
  // out of reach: nothing.
  Eigen::Isometry3d far = X_WF;
  far.translation() = Eigen::Vector3d(2.0, 0.0, 0.5);
  EXPECT_FALSE(SolveArmIkMidArc(arm, far));
}

}  // namespace
}  // namespace graspsynth
