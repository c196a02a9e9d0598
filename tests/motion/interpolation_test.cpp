#include "motion/interpolation.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "kinematics/pose_math.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/motion_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::LineMotion;
using testing::MatricesNear;

// two demonstrations around an object at p_WO, like the paper's neighbouring orientations.
struct Pair {
  Eigen::Vector3d p_WO{-0.25, 0.85, 0.025};
  GraspingMotion m1 =
      LineMotion(p_WO + Eigen::Vector3d(0.1, -0.40, 0.2), p_WO + Eigen::Vector3d(0.09, -0.36, 0.07),
                 0.3, 1.0, 31, 1.1, p_WO, 20 * kDeg);
  GraspingMotion m2 =
      LineMotion(p_WO + Eigen::Vector3d(0.15, -0.39, 0.21),
                 p_WO + Eigen::Vector3d(0.12, -0.35, 0.06), -0.5, 0.8, 47, 1.5, p_WO, 30 * kDeg);
};

TEST(BlendMotions, EndpointsReproduceTheDemonstrations) {
  const Pair p;
  BlendOptions options;
  options.waypoints = 40;
  const GraspingMotion at0 = BlendMotions(p.m1, p.m2, 0.0, options);
  const GraspingMotion at1 = BlendMotions(p.m1, p.m2, 1.0, options);
  const GraspingMotion r1 = Resample(p.m1, 40);
  const GraspingMotion r2 = Resample(p.m2, 40);
  for (size_t i = 0; i < 40; ++i) {
    EXPECT_TRUE(MatricesNear(at0.waypoints[i].p_WH, r1.waypoints[i].p_WH, 0.0));
    EXPECT_TRUE(MatricesNear(at1.waypoints[i].p_WH, r2.waypoints[i].p_WH, 0.0));
    EXPECT_TRUE(MatricesNear(at1.waypoints[i].f, r2.waypoints[i].f, 0.0));
  }
  EXPECT_DOUBLE_EQ(at0.theta, 20 * kDeg);
  EXPECT_DOUBLE_EQ(at1.theta, 30 * kDeg);
  // and they are the original pre-grasp and grasp poses.
  EXPECT_TRUE(MatricesNear(at1.grasp().p_WH, p.m2.grasp().p_WH, 0.0));
  EXPECT_LT(AngleBetween(at0.pregrasp().q_WH, p.m1.pregrasp().q_WH), 1e-15);
}

TEST(BlendMotions, InvalidOptionsAreAnInputErrorNotAnAbort) {
  // the one policy for invalid options (common/valid_options.hpp): a library caller that gives
  // bad options gets an error it can catch and show, as a command line or Python user does.
  const Pair p;
  BlendOptions options;
  options.waypoints = 1;
  GS_EXPECT_THROW_WITH(BlendMotions(p.m1, p.m2, 0.5, options), InputError,
                       "invalid BlendOptions: BlendOptions::waypoints must be at least 2, is 1");
}

TEST(BlendMotions, BlendsEachComponentAsThePaperSays) {
  const Pair p;
  const double t = BlendParameter(24 * kDeg, 20 * kDeg, 30 * kDeg);
  EXPECT_NEAR(t, 0.4, 1e-12);
  const GraspingMotion b = BlendMotions(p.m1, p.m2, t);
  const GraspingMotion r1 = Resample(p.m1, 60);
  const GraspingMotion r2 = Resample(p.m2, 60);
  EXPECT_NEAR(b.theta, 24 * kDeg, 1e-12);
  for (size_t i = 0; i < b.waypoints.size(); ++i) {
    const MotionWaypoint& w = b.waypoints[i];
    const Eigen::Vector3d r_a = r1.waypoints[i].p_WH - p.p_WO;
    const Eigen::Vector3d r_b = r2.waypoints[i].p_WH - p.p_WO;
    // eq. 2: the norm of the object-relative position blends linearly.
    EXPECT_NEAR((w.p_WH - p.p_WO).norm(), 0.6 * r_a.norm() + 0.4 * r_b.norm(), 1e-12);
    // slerp: unit, on the shorter arc, at 40% of the angle.
    EXPECT_NEAR(w.q_WH.norm(), 1.0, 1e-12);
    const double total = AngleBetween(r1.waypoints[i].q_WH, r2.waypoints[i].q_WH);
    EXPECT_NEAR(AngleBetween(r1.waypoints[i].q_WH, w.q_WH), 0.4 * total, 1e-9);
    // eq. 4
    EXPECT_TRUE(MatricesNear(w.f, 0.6 * r1.waypoints[i].f + 0.4 * r2.waypoints[i].f, 1e-15));
  }
  std::string why;
  EXPECT_TRUE(IsWellFormed(b, &why)) << why;
  EXPECT_NEAR(b.duration(), 0.6 * 1.1 + 0.4 * 1.5, 1e-12);
}

TEST(BlendMotions, AntipodalQuaternionsTakeTheShorterArc) {
  Pair p;
  for (MotionWaypoint& w : p.m2.waypoints) w.q_WH.coeffs() = -w.q_WH.coeffs();
  const Pair reference;
  const GraspingMotion a = BlendMotions(p.m1, p.m2, 0.5);
  const GraspingMotion b = BlendMotions(reference.m1, reference.m2, 0.5);
  for (size_t i = 0; i < a.waypoints.size(); ++i) {
    EXPECT_LT(AngleBetween(a.waypoints[i].q_WH, b.waypoints[i].q_WH), 1e-9);
  }
}

TEST(BlendOptions, RejectsTooFewWaypoints) {
  BlendOptions o;
  o.waypoints = 1;
  std::string why;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_EQ(why, "BlendOptions::waypoints must be at least 2, is 1");
}

// a third demonstration at another object position: the placements' blend.
GraspingMotion Third(const Eigen::Vector3d& p_WO) {
  return LineMotion(p_WO + Eigen::Vector3d(0.05, -0.41, 0.19),
                    p_WO + Eigen::Vector3d(0.04, -0.37, 0.08), 0.1, 0.9, 23, 1.3, p_WO, 25 * kDeg);
}

TEST(BlendMotionsWeighted, AWeightOfOneIsThatDemonstrationExactly) {
  const Pair p;
  const GraspingMotion m3 = Third(p.p_WO + Eigen::Vector3d(0.05, 0.05, 0.0));
  BlendOptions options;
  options.waypoints = 40;
  const std::vector<const GraspingMotion*> motions = {&p.m1, &p.m2, &m3};
  for (size_t k = 0; k < 3; ++k) {
    std::vector<double> w(3, 0.0);
    w[k] = 1.0;
    const GraspingMotion blend = BlendMotionsWeighted(motions, w, options);
    const GraspingMotion expected = Resample(*motions[k], 40);
    ASSERT_EQ(blend.waypoints.size(), 40u);
    EXPECT_EQ(blend.theta, expected.theta);
    EXPECT_EQ(blend.p_WO, expected.p_WO);
    for (size_t i = 0; i < 40; ++i) {
      EXPECT_EQ(blend.waypoints[i].p_WH, expected.waypoints[i].p_WH) << k << " " << i;
      EXPECT_EQ(blend.waypoints[i].q_WH.coeffs(), expected.waypoints[i].q_WH.coeffs());
      EXPECT_EQ(blend.waypoints[i].f, expected.waypoints[i].f);
      EXPECT_EQ(blend.waypoints[i].t, expected.waypoints[i].t);
    }
  }
}

TEST(BlendMotionsWeighted, TwoDemonstrationsOfOnePositionGiveThePapersBlend) {
  const Pair p;
  const GraspingMotion m3 = Third(p.p_WO + Eigen::Vector3d(0.05, 0.05, 0.0));
  BlendOptions options;
  options.waypoints = 40;
  for (double t : {0.1, 0.37, 0.5, 0.9}) {
    const GraspingMotion paper = BlendMotions(p.m1, p.m2, t, options);
    // the third motion takes part with weight 0, as a vertex of the cell off the segment.
    const GraspingMotion blend =
        BlendMotionsWeighted({&p.m1, &p.m2, &m3}, {1.0 - t, t, 0.0}, options);
    EXPECT_NEAR(blend.theta, paper.theta, 1e-12);
    EXPECT_TRUE(MatricesNear(blend.p_WO, paper.p_WO, 1e-12));
    for (size_t i = 0; i < 40; ++i) {
      const MotionWaypoint& a = blend.waypoints[i];
      const MotionWaypoint& b = paper.waypoints[i];
      EXPECT_NEAR(a.t, b.t, 1e-12);
      EXPECT_TRUE(MatricesNear(a.p_WH, b.p_WH, 1e-12)) << t << " " << i;
      EXPECT_LT(AngleBetween(a.q_WH, b.q_WH), 1e-12) << t << " " << i;
      EXPECT_TRUE(MatricesNear(a.f, b.f, 1e-12));
    }
  }
}

TEST(BlendMotionsWeighted, BlendsRelativeToEachObjectAndPlacesAtTheWeightedCentre) {
  // the same motion demonstrated at two positions (moved with the object): any blend is that
  // motion at the blended position.
  const Pair p;
  const Eigen::Vector3d shift(0.08, -0.04, 0.0);
  GraspingMotion moved = p.m1;
  moved.p_WO += shift;
  for (MotionWaypoint& w : moved.waypoints) w.p_WH += shift;
  BlendOptions options;
  options.waypoints = 30;
  const GraspingMotion blend = BlendMotionsWeighted({&p.m1, &moved}, {0.25, 0.75}, options);
  const GraspingMotion base = Resample(p.m1, 30);
  EXPECT_TRUE(MatricesNear(blend.p_WO, p.p_WO + 0.75 * shift, 1e-12));
  for (size_t i = 0; i < 30; ++i) {
    EXPECT_TRUE(
        MatricesNear(blend.waypoints[i].p_WH, base.waypoints[i].p_WH + 0.75 * shift, 1e-12));
    EXPECT_LT(AngleBetween(blend.waypoints[i].q_WH, base.waypoints[i].q_WH), 1e-12);
  }
}

}  // namespace
}  // namespace graspsynth
