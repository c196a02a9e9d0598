#include "kinematics/scene_model.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/paths.hpp"
#include "tests/utils/run_command.hpp"

namespace graspsynth {
namespace {

std::string ShippedSceneText() {
  return testing::ReadFileText(std::string(::testing::SourceDir()) + "/models/scene.json");
}

// The shipped scene with one field replaced (a JSON pointer such as "/object/body_radius").
std::string SceneWith(const std::string& pointer, const nlohmann::json& value) {
  nlohmann::json j = nlohmann::json::parse(ShippedSceneText());
  j[nlohmann::json::json_pointer(pointer)] = value;
  return j.dump();
}

TEST(SceneModel, ShippedSceneMatchesTheLayoutStudy) {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  EXPECT_DOUBLE_EQ(scene.object.centre_xy.x(), -0.25);
  EXPECT_DOUBLE_EQ(scene.object.centre_xy.y(), 0.85);
  EXPECT_NEAR(scene.object.handle_offset, -116.0 * M_PI / 180.0, 1e-15);
  EXPECT_DOUBLE_EQ(scene.object.rest_height(), 0.025);
  EXPECT_EQ(scene.grasp_region.shape, GraspRegionModel::Shape::kCylinder);
  EXPECT_DOUBLE_EQ(scene.grasp_region.radius, 0.41);
}

TEST(SceneModel, ObjectPoseTurnsTheHandleWithTheta) {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  const double theta = 60.0 * M_PI / 180.0;
  const Eigen::Isometry3d X_WO = scene.ObjectPose(theta);
  const Eigen::Vector3d handle = X_WO.linear().col(0);
  EXPECT_NEAR(std::atan2(handle.y(), handle.x()) * 180.0 / M_PI, 60.0 - 116.0, 1e-12);
  EXPECT_NEAR(X_WO.translation().z(), 0.025, 1e-15);
  EXPECT_TRUE(testing::MatricesNear(X_WO.linear().col(2), Eigen::Vector3d::UnitZ(), 1e-15));
}

TEST(SceneModel, ObjectShapesFollowTheDescription) {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  const CollisionShape body = scene.object.BodyShape();
  EXPECT_EQ(body.kind, CollisionShape::Kind::kCylinder);
  EXPECT_TRUE(testing::MatricesNear(body.size, Eigen::Vector3d(0.08, 0.05, 0.0), 0.0));
  const CollisionShape handle = scene.object.HandleShape();
  EXPECT_EQ(handle.kind, CollisionShape::Kind::kBox);
  EXPECT_TRUE(testing::MatricesNear(handle.size, Eigen::Vector3d(0.30, 0.024, 0.024), 1e-15));
  // from r 0.08 to 0.38 along x, axis 0.045 m above the table = 0.02 m above the centre.
  EXPECT_TRUE(
      testing::MatricesNear(handle.X_LG.translation(), Eigen::Vector3d(0.23, 0.0, 0.02), 1e-15));
}

TEST(SceneModel, RejectsBadFieldsNamingThem) {
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/format", "graspsynth-scene/2"), "s.json"),
                       InputError,
                       "s.json: field 'format': expected \"graspsynth-scene/1\", found "
                       "\"graspsynth-scene/2\"");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/object/body_radius", -1.0), "s.json"),
                       InputError,
                       "s.json: field 'object.body_radius': expected a number in [0.001, 1], "
                       "found -1.0");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/table/size", {1, 2}), "s.json"), InputError,
                       "s.json: field 'table.size': expected an array of 3 numbers in "
                       "[0.001, 10], found [1,2]");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/table/size", {1, 2, 20}), "s.json"), InputError,
                       "s.json: field 'table.size[2]': expected a number in");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/grasp_region/shape", "cone"), "s.json"),
                       InputError,
                       "s.json: field 'grasp_region.shape': expected \"cylinder\" or "
                       "\"sphere\", found \"cone\"");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/object/handle_end_radius", 0.05), "s.json"),
                       InputError,
                       "s.json: field 'object.handle_end_radius': expected a radius above "
                       "handle_start_radius, found 0.05");
  nlohmann::json j = nlohmann::json::parse(ShippedSceneText());
  j["object"].erase("friction");
  GS_EXPECT_THROW_WITH(ParseSceneModel(j.dump(), "s.json"), InputError,
                       "s.json: field 'object.friction': expected a number in [0, 10], found "
                       "nothing");
  GS_EXPECT_THROW_WITH(ParseSceneModel("{not json", "s.json"), InputError, "s.json: not valid");
  GS_EXPECT_THROW_WITH(LoadSceneModel("/nonexistent/scene.json"), InputError,
                       "/nonexistent/scene.json");
}

}  // namespace
}  // namespace graspsynth
