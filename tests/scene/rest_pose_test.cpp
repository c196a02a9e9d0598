#include "scene/rest_pose.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth {
namespace {

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(DefaultRobotDescriptionPath());
  return robot;
}

// The wrist orientation of a grasp of the handle at 60 deg (as the scripted grasp has it): the
// palm facing down (x_H down), z_H across the handle.
Eigen::Matrix3d PalmDown() {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d across = up.cross(scene.ObjectPose(60.0 * M_PI / 180.0).linear().col(0));
  Eigen::Matrix3d R;
  R.col(0) = -up;
  R.col(2) = across;
  R.col(1) = across.cross(-up);
  return R;
}

TEST(DefaultRestConfiguration, PutsTheWristAboveTheTableTowardTheObject) {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  const Vector7d q = DefaultRestConfiguration(Robot(), scene, PalmDown());
  EXPECT_TRUE(
      ((q.array() >= Robot().arm.lower().array()) && (q.array() <= Robot().arm.upper().array()))
          .all());
  const Eigen::Isometry3d X_WH = ArmFlangePose(Robot().arm, q) * Robot().X_FH;
  const Eigen::Vector2d toward = scene.object_centre_xy.normalized();
  EXPECT_NEAR(X_WH.translation().head<2>().dot(toward), 0.60, 1e-6);
  EXPECT_NEAR(X_WH.translation().z(), scene.table.top_z + 0.30, 1e-6);
  // turned like the grasp, pitched 30 deg about y_H.
  const Eigen::Matrix3d R_expected =
      PalmDown() * Eigen::AngleAxisd(30.0 * M_PI / 180.0, Eigen::Vector3d::UnitY());
  EXPECT_LT((X_WH.linear() - R_expected).norm(), 1e-6);
}

TEST(DefaultRestConfiguration, AnUnreachableRestPoseIsAnInputErrorNamingTheScene) {
  SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  scene.source = "far_table.json";
  scene.table.top_z += 2.0;  // the wrist 2.3 m above the floor of the arm: out of its reach
  GS_EXPECT_THROW_WITH(DefaultRestConfiguration(Robot(), scene, PalmDown()), InputError,
                       "scene far_table.json", "rest pose is out of reach");
}

}  // namespace
}  // namespace graspsynth
