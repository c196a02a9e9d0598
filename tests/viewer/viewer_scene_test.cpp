#include "viewer/viewer_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <random>

#include "common/errors.hpp"
#include "kinematics/hand_model.hpp"
#include "scene/triangle_mesh.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/robot_fixtures.hpp"

namespace graspsynth::viewer {
namespace {

using nlohmann::json;

const RobotModel& Robot() {
  static const RobotModel robot = LoadRobotModel(testing::ShippedUrdfPath());
  return robot;
}

const SceneModel& Scene() {
  static const SceneModel scene = LoadSceneModel(DefaultSceneModelPath());
  return scene;
}

// the robot's links in the scene's order, listed here independently of ViewerRobotBodies.
std::vector<const RigidLink*> RobotLinks(const RobotModel& robot) {
  std::vector<const RigidLink*> links = {&robot.arm.base()};
  for (int i = 1; i <= kArmDof; ++i) links.push_back(&robot.arm.link(i));
  links.push_back(&robot.hand.mount());
  links.push_back(&robot.hand.palm());
  for (int finger = 0; finger < robot.hand.finger_count(); ++finger) {
    for (const RigidLink& link : robot.hand.finger(finger).links) links.push_back(&link);
  }
  return links;
}

Eigen::Isometry3d PoseFromJson(const json& pose) {
  EXPECT_EQ(pose.size(), 7u);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << pose[0].get<double>(), pose[1].get<double>(), pose[2].get<double>();
  const Eigen::Quaterniond q(pose[3].get<double>(), pose[4].get<double>(), pose[5].get<double>(),
                             pose[6].get<double>());
  EXPECT_NEAR(q.norm(), 1.0, 1e-5);
  EXPECT_GE(q.w(), 0.0);
  X.linear() = q.normalized().toRotationMatrix();
  return X;
}

TEST(ViewerScene, ListsEveryLinkWithItsShapes) {
  const json scene = json::parse(ViewerSceneJson(Robot(), Scene(), DefaultViewerCamera(Scene())));
  EXPECT_EQ(scene["format"], "graspsynth-viewer-scene/1");
  const std::vector<const RigidLink*> links = RobotLinks(Robot());
  ASSERT_EQ(links.size(), static_cast<size_t>(ViewerLinkCount(Robot())));
  EXPECT_EQ(ViewerLinkCount(Robot()), 30);  // the Gifu: 8 arm, mount, palm, 20 phalanges
  ASSERT_EQ(scene["links"].size(), links.size());
  int shapes = 0;
  for (size_t i = 0; i < links.size(); ++i) {
    const json& body = scene["links"][i];
    SCOPED_TRACE(links[i]->name);
    EXPECT_EQ(body["name"], links[i]->name);
    EXPECT_EQ(body["group"], i < kArmDof + 1 ? "arm" : "hand");
    ASSERT_EQ(body["shapes"].size(), links[i]->shapes.size());
    for (size_t k = 0; k < links[i]->shapes.size(); ++k) {
      const CollisionShape& expected = links[i]->shapes[k];
      const json& shape = body["shapes"][k];
      EXPECT_TRUE(testing::PosesNear(PoseFromJson(shape["pose"]), expected.X_LG, 1e-12));
      switch (expected.kind) {
        case CollisionShape::Kind::kBox:
          EXPECT_EQ(shape["kind"], "box");
          EXPECT_EQ(shape["size"],
                    json::array({expected.size.x(), expected.size.y(), expected.size.z()}));
          break;
        case CollisionShape::Kind::kCapsule:
        case CollisionShape::Kind::kCylinder:
          EXPECT_EQ(shape["kind"],
                    expected.kind == CollisionShape::Kind::kCapsule ? "capsule" : "cylinder");
          EXPECT_EQ(shape["radius"], expected.size.x());
          EXPECT_EQ(shape["length"], expected.size.y());
          break;
        case CollisionShape::Kind::kSphere:
          EXPECT_EQ(shape["kind"], "sphere");
          EXPECT_EQ(shape["radius"], expected.size.x());
          break;
        case CollisionShape::Kind::kMesh:
          ADD_FAILURE() << "the robot description has primitives only";
          break;
      }
      ++shapes;
    }
  }
  // models/README.md: 11 arm shapes, the mount's and the palm's, one capsule per phalanx and
  // none on the knuckles (link1 of each finger).
  EXPECT_EQ(shapes, 11 + 2 + 15);
  for (int i = 0; i < kArmDof + 3; ++i) EXPECT_FALSE(scene["links"][i]["shapes"].empty());
  for (int finger = 0; finger < Robot().hand.finger_count(); ++finger) {
    const int first = kArmDof + 3 + Robot().hand.JointIndex(finger, 0);
    EXPECT_TRUE(scene["links"][first]["shapes"].empty());
    for (int k = 1; k < static_cast<int>(Robot().hand.finger(finger).links.size()); ++k) {
      EXPECT_EQ(scene["links"][first + k]["shapes"][0]["kind"], "capsule");
    }
  }

  // the pan: the body cylinder at O and the handle bar along +x at the handle's height.
  const ObjectModel& o = Scene().object;
  const json& object = scene["object"];
  EXPECT_EQ(object["group"], "object");
  ASSERT_EQ(object["shapes"].size(), 2u);
  EXPECT_EQ(object["shapes"][0]["kind"], "cylinder");
  EXPECT_EQ(object["shapes"][0]["radius"], 0.08);
  EXPECT_EQ(object["shapes"][0]["length"], 2.0 * o.rest_height);
  EXPECT_EQ(object["shapes"][1]["kind"], "box");
  const Eigen::Isometry3d X_OHandle = PoseFromJson(object["shapes"][1]["pose"]);
  EXPECT_NEAR(X_OHandle.translation().x(), 0.5 * (o.handle->start_radius + o.handle->end_radius),
              1e-12);
  EXPECT_NEAR(X_OHandle.translation().z(), o.handle->axis_height - o.rest_height, 1e-12);

  // the table: a box whose top face is at top_z.
  const json& table = scene["table"];
  ASSERT_EQ(table["shapes"].size(), 1u);
  const Eigen::Isometry3d X_WT = PoseFromJson(table["pose"]);
  EXPECT_NEAR(X_WT.translation().z() + 0.5 * table["shapes"][0]["size"][2].get<double>(),
              Scene().table.top_z, 1e-12);

  EXPECT_EQ(scene["grasp_region"]["radius"], Scene().grasp_region.radius);
  EXPECT_EQ(scene["camera"]["up"], json::array({0, 0, 1}));
}

// A pinhole camera of the page: is world point p within the image of `camera` (aspect 4:3)?
bool InView(const ViewerCamera& camera, const Eigen::Vector3d& p, double aspect = 4.0 / 3.0) {
  const Eigen::Vector3d forward = (camera.target - camera.eye).normalized();
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const Eigen::Vector3d d = p - camera.eye;
  const double depth = d.dot(forward);
  if (depth <= 0.0) return false;
  const double half = std::tan(0.5 * camera.fov_deg * M_PI / 180.0);
  return std::abs(d.dot(up) / depth) < half && std::abs(d.dot(right) / depth) < half * aspect;
}

// A mesh part goes to the page as its vertices and triangles (flat arrays), at its pose; a part
// that touches only the table (a support) is not drawn.
TEST(ViewerScene, MeshPartsAreSentAsIndexedTriangles) {
  SceneModel scene = Scene();
  auto tetra = std::make_shared<TriangleMesh>();
  tetra->vertices = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}, {0, 0, 0.1}};
  tetra->triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  ObjectPart part;
  part.name = "tetra";
  part.shape.kind = CollisionShape::Kind::kMesh;
  part.shape.mesh = tetra;
  part.shape.X_LG.translation() << 0.0, 0.0, -0.05;
  part.mass = 0.1;
  scene.object.parts = {part, scene.object.parts[2]};
  ASSERT_EQ(scene.object.parts[1].touches, PartContact::kTable);
  const json j = json::parse(ViewerSceneJson(Robot(), scene, DefaultViewerCamera(scene)));
  const json& shapes = j["object"]["shapes"];
  ASSERT_EQ(shapes.size(), 1u);
  EXPECT_EQ(shapes[0]["kind"], "mesh");
  EXPECT_EQ(shapes[0]["vertices"].size(), 12u);
  EXPECT_EQ(shapes[0]["vertices"][3], 0.1);  // x of the second vertex
  EXPECT_EQ(shapes[0]["triangles"], json::array({0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3}));
  EXPECT_EQ(PoseFromJson(shapes[0]["pose"]).translation().z(), -0.05);
}

TEST(ViewerScene, DefaultCameraSeesTheArmAndTheObject) {
  const ViewerCamera camera = DefaultViewerCamera(Scene());
  const Eigen::Vector3d p_WO = Scene().ObjectPose(0.0).translation();
  EXPECT_TRUE(InView(camera, Eigen::Vector3d::Zero()));         // arm base
  EXPECT_TRUE(InView(camera, Eigen::Vector3d(0.0, 0.0, 1.0)));  // the raised arm
  EXPECT_TRUE(InView(camera, p_WO));                            // the pan
  EXPECT_GT(camera.eye.z(), Scene().table.top_z + 0.5);         // from above the table
}

TEST(ViewerScene, FramePosesEqualForwardKinematics) {
  const RobotModel& robot = Robot();
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    ViewerState state;
    for (int j = 0; j < kArmDof; ++j) {
      state.arm[j] =
          std::uniform_real_distribution<>(robot.arm.lower()[j], robot.arm.upper()[j])(rng);
    }
    for (int k = 0; k < kHandDof; ++k) {
      state.hand[k] =
          std::uniform_real_distribution<>(robot.hand.lower()[k], robot.hand.upper()[k])(rng);
    }
    state.t = 0.25 * trial;
    state.X_WO = Scene().ObjectPose(0.1 * trial);
    state.text = "trial \"" + std::to_string(trial) + "\"\nnext line";

    const json frame = json::parse(ViewerFrameJson(robot, state));
    EXPECT_DOUBLE_EQ(frame["t"].get<double>(), state.t);
    EXPECT_EQ(frame["text"], state.text);
    EXPECT_TRUE(testing::PosesNear(PoseFromJson(frame["object"]), state.X_WO, 1e-5));
    ASSERT_EQ(frame["links"].size(), static_cast<size_t>(ViewerLinkCount(robot)));

    ArmFrames arm;
    ArmLinkFrames(robot.arm, state.arm, &arm);
    for (int i = 0; i <= kArmDof; ++i) {
      EXPECT_TRUE(testing::PosesNear(PoseFromJson(frame["links"][i]), arm.X_WL[i], 1e-5)) << i;
    }
    // the flange through the DH table, independent of the link frames.
    const Eigen::Isometry3d X_WF = ArmFlangePose(robot.arm, state.arm);
    EXPECT_TRUE(testing::PosesNear(PoseFromJson(frame["links"][kArmDof]), X_WF, 1e-5));
    const Eigen::Isometry3d X_WH = X_WF * robot.X_FH;
    EXPECT_TRUE(testing::PosesNear(PoseFromJson(frame["links"][kArmDof + 1]), X_WH, 1e-5));
    HandFrames hand;
    HandLinkFrames(robot.hand, state.hand, &hand);
    EXPECT_TRUE(
        testing::PosesNear(PoseFromJson(frame["links"][kArmDof + 2]), X_WH * hand.X_HP, 1e-5));
    for (int finger = 0; finger < robot.hand.finger_count(); ++finger) {
      for (int k = 0; k < static_cast<int>(robot.hand.finger(finger).links.size()); ++k) {
        const int index = kArmDof + 3 + robot.hand.JointIndex(finger, k);
        EXPECT_TRUE(testing::PosesNear(PoseFromJson(frame["links"][index]),
                                       X_WH * hand.X_HL[finger][k], 1e-5))
            << index;
      }
    }
  }
}

TEST(ViewerScene, FrameIsCompactAndWritesNonFiniteValuesAsNull) {
  ViewerState state;
  state.t = 1.0 / 3.0;
  const std::string text = ViewerFrameJson(Robot(), state);
  EXPECT_LT(text.size(), 64u * static_cast<size_t>(ViewerLinkCount(Robot())));
  EXPECT_NE(text.find("\"t\":0.333333,"), std::string::npos) << text;
  EXPECT_EQ(text.find("-0,"), std::string::npos) << text;
  EXPECT_EQ(text.find('\n'), std::string::npos);

  state.X_WO.translation().x() = std::nan("");
  const json frame = json::parse(ViewerFrameJson(Robot(), state));
  EXPECT_TRUE(frame["object"][0].is_null());
}

// A physics replay's frame carries its contacts and outcome; a frame without them (the live
// teleoperation view) has neither key.
TEST(ViewerScene, FrameCarriesContactsAndOutcomeOnlyWhenThereAreSome) {
  ViewerState state;
  const std::string plain = ViewerFrameJson(Robot(), state);
  EXPECT_EQ(plain.find("contacts"), std::string::npos);
  EXPECT_EQ(plain.find("outcome"), std::string::npos);
  state.contacts = {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(-0.25, 0.85, 0.0401234567)};
  state.outcome = ViewerOutcome{false, "FAILED (dropped): \"slipped\""};
  const json frame = json::parse(ViewerFrameJson(Robot(), state));
  ASSERT_EQ(frame["contacts"].size(), 2u);
  EXPECT_EQ(frame["contacts"][0], json::parse("[0.1, 0.2, 0.3]"));
  EXPECT_EQ(frame["contacts"][1][2], 0.040123);
  EXPECT_EQ(frame["outcome"]["success"], false);
  EXPECT_EQ(frame["outcome"]["text"], "FAILED (dropped): \"slipped\"");
}

TEST(ViewerScene, ParsesCameraPlacements) {
  ViewerCamera defaults;
  defaults.target = Eigen::Vector3d(0.1, 0.2, 0.3);
  const ViewerCamera eye_only = ParseViewerCamera("2,-1,1.5", defaults);
  EXPECT_TRUE(testing::MatricesNear(eye_only.eye, Eigen::Vector3d(2, -1, 1.5), 0.0));
  EXPECT_TRUE(testing::MatricesNear(eye_only.target, defaults.target, 0.0));
  const ViewerCamera both = ParseViewerCamera("2, -1, 1.5, 0, 0.5, 0.25", defaults);
  EXPECT_TRUE(testing::MatricesNear(both.target, Eigen::Vector3d(0, 0.5, 0.25), 0.0));

  GS_EXPECT_THROW_WITH(ParseViewerCamera("1,2,3,4", defaults), InputError, "'1,2,3,4'",
                       "4 numbers");
  GS_EXPECT_THROW_WITH(ParseViewerCamera("1,x,3", defaults), InputError, "'1,x,3'", "x");
  GS_EXPECT_THROW_WITH(ParseViewerCamera("0.1,0.2,0.3", defaults), InputError,
                       "the eye is at the target");
}

}  // namespace
}  // namespace graspsynth::viewer
