#include "solver/line_principle.hpp"

#include <gtest/gtest.h>

#include "kinematics/pose_math.hpp"
#include "solver/bracket.hpp"
#include "tests/solver/synthesis_fixtures.hpp"

namespace graspsynth {
namespace {

using testing::Library406080;
using testing::ShippedSimulationModel;
using testing::SideSwitchLibrary;

const SceneModel& Scene() { return ShippedSimulationModel().scene(); }

// The models at orientation theta (rad) of the shipped scene, its object pose computed once.
Eigen::Isometry3d GraspPoseAt(const LinePrincipleModel& m, double theta, int side) {
  const Placement placement{theta, {}};
  return LinePrincipleGraspPose(m, placement, Scene().ObjectPose(placement), side);
}
GraspingMotion MotionAt(const LinePrincipleModel& m, double theta, int side) {
  const Placement placement{theta, {}};
  return LinePrincipleMotion(m, placement, Scene().ObjectPose(placement), side);
}

TEST(LinePrinciple, TheMotionStandsAtTheObjectPoseItIsGiven) {
  // the object pose is the caller's: the models place the grasp relative to it.
  const LinePrincipleModel m = FitLinePrinciple(Library406080(), Scene());
  ASSERT_TRUE(m.valid) << m.message;
  const Placement placement{50.0 * kDeg, {}};
  const Eigen::Isometry3d X_WO = Scene().ObjectPose(placement);
  Eigen::Isometry3d X_shifted = X_WO;
  X_shifted.translation() += Eigen::Vector3d(0.1, -0.05, 0.0);
  const GraspingMotion a = LinePrincipleMotion(m, placement, X_WO, +1);
  const GraspingMotion b = LinePrincipleMotion(m, placement, X_shifted, +1);
  EXPECT_EQ(a.p_WO, X_WO.translation());
  EXPECT_EQ(b.p_WO, X_shifted.translation());
  EXPECT_EQ(a.theta, placement.theta);
  EXPECT_LT((b.grasp().p_WH - a.grasp().p_WH - Eigen::Vector3d(0.1, -0.05, 0.0)).norm(), 1e-12);
  EXPECT_TRUE(b.grasp().q_WH.isApprox(a.grasp().q_WH, 1e-12));
}

TEST(LinePrinciple, ReproducesTheLibrarysGraspsInsideTheRange) {
  const LinePrincipleModel m = FitLinePrinciple(Library406080(), Scene());
  ASSERT_TRUE(m.valid) << m.message;
  EXPECT_EQ(m.sides[1].entries, 3);
  EXPECT_EQ(m.sides[0].entries, 0);
  for (const LibraryEntry& e : Library406080().entries) {
    const Eigen::Isometry3d X = GraspPoseAt(m, e.theta_deg * kDeg, +1);
    const Eigen::Isometry3d Y = Eigen::Translation3d(e.motion.grasp().p_WH) * e.motion.grasp().q_WH;
    const PoseDistance d = DistanceBetween(X, Y);
    // three grasps on a circle about the object centre are not on a line: a few cm; the
    // height, the hand's orientation and the fingers are the demonstration's.
    EXPECT_LT(d.translation, 0.03) << e.theta_deg;
    EXPECT_NEAR(X.translation().z(), Y.translation().z(), 1e-12) << e.theta_deg;
    EXPECT_LT(d.rotation, 1e-9) << e.theta_deg;
    const GraspingMotion g = MotionAt(m, e.theta_deg * kDeg, +1);
    EXPECT_LT((g.grasp().f - e.motion.grasp().f).cwiseAbs().maxCoeff(), 1e-12) << e.theta_deg;
  }
}

TEST(LinePrinciple, TheHandleLiesInTheHandWhereTheScriptedGraspPutsIt) {
  const LinePrincipleModel m = FitLinePrinciple(Library406080(), Scene());
  ASSERT_TRUE(m.valid);
  EXPECT_LT((m.handle_in_hand - RobotGraspOf(ShippedSimulationModel().robot()).bar_in_hand).norm(),
            1e-3);
}

TEST(LinePrinciple, MotionsOutsideTheRangeAreWellFormedAndEndAtTheModelledGrasp) {
  const LinePrincipleModel m = FitLinePrinciple(Library406080(), Scene());
  ASSERT_TRUE(m.valid);
  for (double theta_deg : {0.0, 10.0, 20.0, 100.0, 110.0, 120.0}) {
    const GraspingMotion g = MotionAt(m, theta_deg * kDeg, +1);
    std::string why;
    ASSERT_TRUE(IsWellFormed(g, &why)) << theta_deg << ": " << why;
    EXPECT_EQ(g.waypoints.size(), 40u);
    const Eigen::Isometry3d X = GraspPoseAt(m, theta_deg * kDeg, +1);
    EXPECT_LT((g.grasp().p_WH - X.translation()).norm(), 1e-12);
    // the hand's long axis lies across the handle (within the fitted yaw's drift).
    const Eigen::Vector3d h = Scene().ObjectPose(theta_deg * kDeg).linear().col(0);
    EXPECT_LT(std::abs((g.grasp().q_WH * Eigen::Vector3d::UnitZ()).dot(h)), 0.2) << theta_deg;
    // the pre-grasp is above the grasp, as in every demonstration.
    EXPECT_GT(g.pregrasp().p_WH.z(), g.grasp().p_WH.z() + 0.03);
  }
}

TEST(LinePrinciple, OrientationIsFittedPerSideOfTheHandle) {
  const LinePrincipleModel m = FitLinePrinciple(SideSwitchLibrary(), Scene());
  ASSERT_TRUE(m.valid) << m.message;
  EXPECT_EQ(m.sides[0].entries, 2);
  EXPECT_EQ(m.sides[1].entries, 2);
  EXPECT_EQ(m.entry_sides, (std::vector<int>{-1, -1, 1, 1}));
  // across the handle on either side: yaw relative to the handle near -90 and +90 deg.
  EXPECT_NEAR(m.sides[0].At(45.0 * kDeg).yaw, -90.0 * kDeg, 1e-6);
  EXPECT_NEAR(m.sides[1].At(45.0 * kDeg).yaw, 90.0 * kDeg, 1e-6);
  EXPECT_TRUE(m.sides[0].has_line);
  // each side's grip is its own demonstrations': at 45 deg, the nearest of that side's.
  const GraspLibrary& library = SideSwitchLibrary();
  EXPECT_EQ(MotionAt(m, 45.0 * kDeg, -1).grasp().f, library.entries[1].motion.grasp().f);
  EXPECT_EQ(MotionAt(m, 45.0 * kDeg, +1).grasp().f, library.entries[2].motion.grasp().f);
  const Eigen::Isometry3d left = GraspPoseAt(m, 45.0 * kDeg, -1);
  EXPECT_EQ(HandleSide(Scene(), 45.0 * kDeg, left.translation(), 0.01), -1);
  const Eigen::Isometry3d right = GraspPoseAt(m, 45.0 * kDeg, +1);
  EXPECT_EQ(HandleSide(Scene(), 45.0 * kDeg, right.translation(), 0.01), 1);
}

TEST(LinePrinciple, TheHandsTiltFollowsTheOrientationAndIsHeldOutsideTheRange) {
  // the 40, 60 and 80 deg grasps pitched fingers-down by 0, 10 and 20 deg (about y_H).
  GraspLibrary library = Library406080();
  auto pitch_at = [](double theta_deg) { return (theta_deg - 40.0) / 2.0 * kDeg; };
  for (LibraryEntry& e : library.entries) {
    const Eigen::Quaterniond tilt(
        Eigen::AngleAxisd(pitch_at(e.theta_deg), Eigen::Vector3d::UnitY()));
    for (MotionWaypoint& w : e.motion.waypoints) w.q_WH = (w.q_WH * tilt).normalized();
  }
  const LinePrincipleModel m = FitLinePrinciple(library, Scene());
  ASSERT_TRUE(m.valid) << m.message;
  // how far the fingers point below the table plane at the modelled grasp.
  auto pitch_of = [&](double theta_deg) {
    const Eigen::Isometry3d X = GraspPoseAt(m, theta_deg * kDeg, +1);
    return std::asin(-X.linear().col(2).z());
  };
  for (double theta_deg : {40.0, 50.0, 60.0, 80.0}) {
    EXPECT_NEAR(pitch_of(theta_deg), pitch_at(theta_deg) + pitch_of(40.0), 0.5 * kDeg) << theta_deg;
  }
  // outside the demonstrated range the tilt of the nearest end is kept.
  EXPECT_NEAR(pitch_of(110.0), pitch_of(80.0), 1e-9);
  EXPECT_NEAR(pitch_of(10.0), pitch_of(40.0), 1e-9);
}

TEST(LinePrinciple, OneEntryIsNotEnough) {
  GraspLibrary one;
  one.entries.push_back(Library406080().entries[0]);
  const LinePrincipleModel m = FitLinePrinciple(one, Scene());
  EXPECT_FALSE(m.valid);
  EXPECT_NE(m.message.find("two"), std::string::npos);
}

TEST(LinePrinciple, WeakEntriesAreLeftOutOfTheFits) {
  GraspLibrary library = SideSwitchLibrary();  // 30, 40 deg left of the handle; 50, 60 right
  const LinePrincipleModel all = FitLinePrinciple(library, Scene());
  EXPECT_EQ(all.fitted_entries, 4);
  // a weak 60 deg entry: the right side's models come from 50 deg alone (no line of its own),
  // the sides of every entry are still known.
  library.entries[3].score = 0.2;
  const LinePrincipleModel robust = FitLinePrinciple(library, Scene());
  ASSERT_TRUE(robust.valid) << robust.message;
  EXPECT_EQ(robust.fitted_entries, 3);
  ASSERT_EQ(robust.entry_sides.size(), 4u);
  EXPECT_EQ(robust.entry_sides[3], all.entry_sides[3]);
  EXPECT_EQ(robust.sides[1].entries, 1);
  EXPECT_FALSE(robust.sides[1].has_line);
  // fewer than two robust entries: every entry is used.
  for (int k = 0; k < 3; ++k) library.entries[k].score = 0.1;
  EXPECT_EQ(FitLinePrinciple(library, Scene()).fitted_entries, 4);
}

}  // namespace
}  // namespace graspsynth
