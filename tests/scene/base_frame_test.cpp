// Tests of scene/base_frame.hpp: a scene re-expressed in a robot's base frame.

#include "scene/base_frame.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

const SceneModel& Shipped() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}

Eigen::Isometry3d Base(double x, double y, double z, double yaw_deg = 0.0) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  X.translation() = Eigen::Vector3d(x, y, z);
  return X;
}

TEST(SceneInBaseFrame, ARobotAtTheOriginKeepsTheScenesBits) {
  const SceneModel s = SceneInBaseFrame(Shipped(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(s.table.top_z, Shipped().table.top_z);
  EXPECT_EQ(s.table.centre_xy, Shipped().table.centre_xy);
  EXPECT_EQ(s.object_centre_xy, Shipped().object_centre_xy);
  EXPECT_EQ(s.object_yaw_offset, Shipped().object_yaw_offset);
  EXPECT_EQ(s.ObjectPose(1.0).matrix(), Shipped().ObjectPose(1.0).matrix());
  EXPECT_EQ(TablePointInScene(s, Eigen::Vector2d(-0.3, 0.9)), Eigen::Vector2d(-0.3, 0.9));
}

// the iiwa's base (docs/robot-file-draft.md): the scene seen from it is the world's, shifted.
TEST(SceneInBaseFrame, EveryPoseIsTheWorldsSeenFromTheBase) {
  const Eigen::Isometry3d X_WB = Base(0.20, -0.20, 0.01);
  const SceneModel s = SceneInBaseFrame(Shipped(), X_WB);
  EXPECT_TRUE(s.X_WS.isApprox(X_WB, 0.0));
  EXPECT_NEAR(s.object_centre_xy.x(), -0.45, 1e-15);
  EXPECT_NEAR(s.object_centre_xy.y(), 1.05, 1e-15);
  EXPECT_NEAR(s.table.top_z, -0.01, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(s.table.centre_xy, Eigen::Vector2d(-0.45, 1.05), 1e-15));
  for (double theta : {20.0, 60.0, 100.0}) {
    const Placement at{theta * kDeg, Eigen::Vector2d(-0.3, 0.9)};
    const Placement at_B{theta * kDeg, TablePointInScene(s, *at.xy)};
    EXPECT_TRUE(testing::PosesNear(s.ObjectPose(theta * kDeg),
                                   X_WB.inverse() * Shipped().ObjectPose(theta * kDeg), 1e-12));
    EXPECT_TRUE(
        testing::PosesNear(s.ObjectPose(at_B), X_WB.inverse() * Shipped().ObjectPose(at), 1e-12));
  }
  // a second call for the same robot changes nothing: the scene is already in its frame.
  const SceneModel again = SceneInBaseFrame(s, X_WB);
  EXPECT_EQ(again.object_centre_xy, s.object_centre_xy);
  EXPECT_EQ(again.table.top_z, s.table.top_z);
}

TEST(SceneInBaseFrame, ATurnedBaseIsRefusedNamingTheScene) {
  GS_EXPECT_THROW_WITH(SceneInBaseFrame(Shipped(), Base(0.2, -0.2, 0.0, 10.0)), InputError,
                       Shipped().source, "turned 10 deg", "only a base shifted");
}

}  // namespace
}  // namespace graspsynth
