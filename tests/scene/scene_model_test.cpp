#include "scene/scene_model.hpp"

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

// The shipped scene with one field replaced (a JSON pointer such as "/table/size").
std::string SceneWith(const std::string& pointer, const nlohmann::json& value) {
  nlohmann::json j = nlohmann::json::parse(ShippedSceneText());
  j[nlohmann::json::json_pointer(pointer)] = value;
  return j.dump();
}

TEST(SceneModel, ShippedSceneMatchesTheLayoutStudy) {
  const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  EXPECT_DOUBLE_EQ(scene.object_centre_xy.x(), -0.25);
  EXPECT_DOUBLE_EQ(scene.object_centre_xy.y(), 0.85);
  EXPECT_NEAR(scene.object_yaw_offset, -116.0 * M_PI / 180.0, 1e-15);
  EXPECT_EQ(scene.object.name, "pan");
  EXPECT_DOUBLE_EQ(scene.object.rest_height, 0.025);
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
  const CollisionShape& body = scene.object.parts[0].shape;
  EXPECT_EQ(body.kind, CollisionShape::Kind::kCylinder);
  EXPECT_TRUE(testing::MatricesNear(body.size, Eigen::Vector3d(0.08, 0.05, 0.0), 0.0));
  const CollisionShape& handle = scene.object.parts[1].shape;
  EXPECT_EQ(handle.kind, CollisionShape::Kind::kBox);
  EXPECT_TRUE(testing::MatricesNear(handle.size, Eigen::Vector3d(0.30, 0.024, 0.024), 1e-15));
  // from r 0.08 to 0.38 along x, axis 0.045 m above the table = 0.02 m above the centre.
  EXPECT_TRUE(
      testing::MatricesNear(handle.X_LG.translation(), Eigen::Vector3d(0.23, 0.0, 0.02), 1e-15));
}

// The scene of the format before objects were files: the pan inline.
constexpr const char* kSceneV1 = R"({
  "format": "graspsynth-scene/1",
  "table": {"top_z": 0.0, "centre_xy": [-0.25, 0.85], "size": [0.9, 0.9, 0.05], "friction": 0.8},
  "object": {
    "name": "pan", "centre": [-0.25, 0.85], "handle_offset_deg": -116.0,
    "body_radius": 0.08, "body_height": 0.05, "handle_start_radius": 0.08,
    "handle_end_radius": 0.38, "handle_width": 0.024, "handle_thickness": 0.024,
    "handle_axis_height": 0.045, "body_mass": 0.2, "handle_mass": 0.07, "friction": 1.0
  },
  "grasp_region": {"shape": "cylinder", "radius": 0.41, "height": 1.0}
})";

TEST(SceneModel, Format1WithThePanInlineIsStillRead) {
  const SceneModel v1 = ParseSceneModel(kSceneV1, "old.json");
  const SceneModel v2 = LoadSceneModel(DefaultSceneModelPath());
  EXPECT_EQ(v1.object_centre_xy, v2.object_centre_xy);
  EXPECT_EQ(v1.object_yaw_offset, v2.object_yaw_offset);
  EXPECT_EQ(v1.object.parts.size(), v2.object.parts.size());
  EXPECT_EQ(v1.object.rest_height, v2.object.rest_height);
  EXPECT_EQ(v1.object.Inertia().mass, v2.object.Inertia().mass);
  EXPECT_TRUE(testing::MatricesNear(v1.ObjectPose(0.3).matrix(), v2.ObjectPose(0.3).matrix(), 0.0));
  EXPECT_EQ(v1.object.Inertia().p_OC, v2.object.Inertia().p_OC);
  EXPECT_EQ(v1.object.Inertia().I_C, v2.object.Inertia().I_C);
  nlohmann::json j = nlohmann::json::parse(kSceneV1);
  j["object"]["handle_end_radius"] = 0.05;
  GS_EXPECT_THROW_WITH(ParseSceneModel(j.dump(), "s.json"), InputError,
                       "s.json: field 'object.handle_end_radius': expected a radius above "
                       "handle_start_radius, found 0.05");
  j = nlohmann::json::parse(kSceneV1);
  j["object"]["body_radius"] = -1.0;
  GS_EXPECT_THROW_WITH(ParseSceneModel(j.dump(), "s.json"), InputError,
                       "s.json: field 'object.body_radius': expected a number in [0.001, 1], "
                       "found -1.0");
}

TEST(SceneModel, RejectsBadFieldsNamingThem) {
  const std::string dir = std::string(::testing::SourceDir()) + "/models";
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/format", "graspsynth-scene/9"), "s.json", dir),
                       InputError,
                       "s.json: field 'format': expected \"graspsynth-scene/2\", found "
                       "\"graspsynth-scene/9\"");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/table/size", {1, 2}), "s.json", dir), InputError,
                       "s.json: field 'table.size': expected an array of 3 numbers in "
                       "[0.001, 10], found [1,2]");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/table/size", {1, 2, 20}), "s.json", dir),
                       InputError, "s.json: field 'table.size[2]': expected a number in");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/grasp_region/shape", "cone"), "s.json", dir),
                       InputError,
                       "s.json: field 'grasp_region.shape': expected \"cylinder\" or "
                       "\"sphere\", found \"cone\"");
  GS_EXPECT_THROW_WITH(
      ParseSceneModel(SceneWith("/object", "objects/teapot.json"), "s.json", dir), InputError,
      "s.json: field 'object': cannot read object description '" + dir + "/objects/teapot.json'");
  GS_EXPECT_THROW_WITH(ParseSceneModel(SceneWith("/object", 3), "s.json", dir), InputError,
                       "s.json: field 'object': expected a string");
  nlohmann::json j = nlohmann::json::parse(ShippedSceneText());
  j.erase("object_centre");
  GS_EXPECT_THROW_WITH(ParseSceneModel(j.dump(), "s.json", dir), InputError,
                       "s.json: field 'object_centre': expected an array of 2 numbers");
  GS_EXPECT_THROW_WITH(ParseSceneModel("{not json", "s.json"), InputError, "s.json: not valid");
  GS_EXPECT_THROW_WITH(LoadSceneModel("/nonexistent/scene.json"), InputError,
                       "/nonexistent/scene.json");
}

}  // namespace
}  // namespace graspsynth
