#include "viewer/viewer_scene.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "common/text_input.hpp"
#include "kinematics/hand_model.hpp"
#include "kinematics/pose_math.hpp"
#include "scene/triangle_mesh.hpp"

namespace graspsynth::viewer {
namespace {

using nlohmann::json;

// pose as [x, y, z, qw, qx, qy, qz] (quaternion sign-normalized).
json PoseJson(const Eigen::Isometry3d& X) {
  const Eigen::Quaterniond q = Canonical(Eigen::Quaterniond(X.linear()));
  const Eigen::Vector3d& p = X.translation();
  return json::array({p.x(), p.y(), p.z(), q.w(), q.x(), q.y(), q.z()});
}

json VectorJson(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json ShapeJson(const CollisionShape& s) {
  json j;
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      j = {{"kind", "box"}, {"size", VectorJson(s.size)}};
      break;
    case CollisionShape::Kind::kCapsule:
      j = {{"kind", "capsule"}, {"radius", s.size.x()}, {"length", s.size.y()}};
      break;
    case CollisionShape::Kind::kCylinder:
      j = {{"kind", "cylinder"}, {"radius", s.size.x()}, {"length", s.size.y()}};
      break;
    case CollisionShape::Kind::kSphere:
      j = {{"kind", "sphere"}, {"radius", s.size.x()}};
      break;
    case CollisionShape::Kind::kMesh: {
      json vertices = json::array(), triangles = json::array();
      for (const Eigen::Vector3d& v : s.mesh->vertices) {
        vertices.insert(vertices.end(), {v.x(), v.y(), v.z()});
      }
      for (const std::array<int, 3>& t : s.mesh->triangles) {
        triangles.insert(triangles.end(), {t[0], t[1], t[2]});
      }
      j = {{"kind", "mesh"}, {"vertices", vertices}, {"triangles", triangles}};
      break;
    }
  }
  j["pose"] = PoseJson(s.X_LG);
  return j;
}

json BodyJson(const ViewerBody& body) {
  json shapes = json::array();
  for (const CollisionShape& s : body.shapes) shapes.push_back(ShapeJson(s));
  return {{"name", body.name}, {"group", body.group}, {"shapes", shapes}};
}

// a number rounded to 1e-6 in its shortest fixed form ("0.25", "-1.5", "0"); null when not
// finite, which the page skips.
void AppendNumber(double v, std::string* out) {
  if (!std::isfinite(v)) {
    out->append("null");
    return;
  }
  char buffer[64];
  const int n = std::snprintf(buffer, sizeof(buffer), "%.6f", v);
  std::string_view text(buffer, n > 0 ? static_cast<size_t>(n) : 0);
  while (text.size() > 1 && text.back() == '0') text.remove_suffix(1);
  if (!text.empty() && text.back() == '.') text.remove_suffix(1);
  if (text == "-0") text = "0";
  out->append(text);
}

void AppendPose(const Eigen::Isometry3d& X, std::string* out) {
  const Eigen::Quaterniond q = Canonical(Eigen::Quaterniond(X.linear()));
  const double values[7] = {
      X.translation().x(), X.translation().y(), X.translation().z(), q.w(), q.x(), q.y(), q.z()};
  out->push_back('[');
  for (int i = 0; i < 7; ++i) {
    if (i > 0) out->push_back(',');
    AppendNumber(values[i], out);
  }
  out->push_back(']');
}

}  // namespace

ViewerCamera DefaultViewerCamera(const SceneModel& scene) {
  const Eigen::Vector2d centre = scene.object_centre_xy;
  const Eigen::Vector2d toward =
      centre.norm() > 1e-9 ? Eigen::Vector2d(centre.normalized()) : Eigen::Vector2d::UnitX();
  // to the right of the base-to-object line, swung 35 deg toward the object's side.
  const Eigen::Vector2d side(toward.y(), -toward.x());
  const double swing = 35.0 * kDeg;
  const Eigen::Vector2d horizontal = std::cos(swing) * side + std::sin(swing) * toward;
  const double elevation = 30.0 * kDeg;
  const double distance = 2.6;
  ViewerCamera camera;
  camera.target << 0.55 * centre, scene.table.top_z + 0.3;
  camera.eye = camera.target + distance * Eigen::Vector3d(std::cos(elevation) * horizontal.x(),
                                                          std::cos(elevation) * horizontal.y(),
                                                          std::sin(elevation));
  return camera;
}

ViewerCamera ParseViewerCamera(std::string_view text, const ViewerCamera& defaults) {
  std::string why;
  const auto values = ParseNumberList(text, 0, &why);
  if (!values) throw InputError("camera placement '" + std::string(text) + "': " + why);
  if (values->size() != 3 && values->size() != 6) {
    throw InputError("camera placement '" + std::string(text) + "' has " +
                     std::to_string(values->size()) +
                     " numbers; expected EX,EY,EZ or EX,EY,EZ,TX,TY,TZ (metres, world)");
  }
  ViewerCamera camera = defaults;
  camera.eye << (*values)[0], (*values)[1], (*values)[2];
  if (values->size() == 6) camera.target << (*values)[3], (*values)[4], (*values)[5];
  if ((camera.eye - camera.target).norm() < 1e-6) {
    throw InputError("camera placement '" + std::string(text) + "': the eye is at the target");
  }
  return camera;
}

int ViewerLinkCount(const RobotModel& robot) { return kArmDof + 1 + 2 + robot.hand.joint_count(); }

std::vector<ViewerBody> ViewerRobotBodies(const RobotModel& robot) {
  std::vector<ViewerBody> bodies;
  bodies.reserve(static_cast<size_t>(ViewerLinkCount(robot)));
  bodies.push_back({robot.arm.base().name, "arm", robot.arm.base().shapes});
  for (int i = 1; i <= kArmDof; ++i) {
    bodies.push_back({robot.arm.link(i).name, "arm", robot.arm.link(i).shapes});
  }
  bodies.push_back({robot.hand.mount().name, "hand", robot.hand.mount().shapes});
  bodies.push_back({robot.hand.palm().name, "hand", robot.hand.palm().shapes});
  for (const Finger& finger : robot.hand.fingers()) {
    for (const RigidLink& link : finger.links) bodies.push_back({link.name, "hand", link.shapes});
  }
  return bodies;
}

ViewerBody ViewerObjectBody(const ObjectModel& o) {
  ViewerBody body{o.name, "object", {}};
  for (const ObjectPart& part : o.parts) {
    if (part.touches_robot()) body.shapes.push_back(part.shape);
  }
  return body;
}

std::string ViewerSceneJson(const RobotModel& robot, const SceneModel& scene,
                            const ViewerCamera& camera) {
  json links = json::array();
  for (const ViewerBody& body : ViewerRobotBodies(robot)) links.push_back(BodyJson(body));

  CollisionShape table_box;
  table_box.kind = CollisionShape::Kind::kBox;
  table_box.size = scene.table.size;
  Eigen::Isometry3d X_WT = Eigen::Isometry3d::Identity();
  X_WT.translation() << scene.table.centre_xy, scene.table.top_z - 0.5 * scene.table.size.z();
  json table = BodyJson({"table", "table", {table_box}});
  table["pose"] = PoseJson(X_WT);

  const GraspRegionModel& region = scene.grasp_region;
  const Eigen::Vector3d p_WO = scene.ObjectPose(0.0).translation();
  json grasp_region = {
      {"shape", region.shape == GraspRegionModel::Shape::kCylinder ? "cylinder" : "sphere"},
      {"centre", VectorJson(p_WO)},
      {"radius", region.radius}};
  if (region.shape == GraspRegionModel::Shape::kCylinder) grasp_region["height"] = region.height;

  const json document = {{"format", kViewerSceneFormat},
                         {"robot", robot.source},
                         {"scene", scene.source},
                         {"links", links},
                         {"object", BodyJson(ViewerObjectBody(scene.object))},
                         {"table", table},
                         {"grasp_region", grasp_region},
                         {"camera",
                          {{"eye", VectorJson(camera.eye)},
                           {"target", VectorJson(camera.target)},
                           {"up", json::array({0, 0, 1})},
                           {"fov_deg", camera.fov_deg}}}};
  return document.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::vector<Eigen::Isometry3d> ViewerLinkPoses(const RobotModel& robot,
                                               const Eigen::Ref<const Vector7d>& q,
                                               const Eigen::Ref<const HandVector>& f) {
  ArmFrames arm;
  ArmLinkFrames(robot.arm, q, &arm);
  HandFrames hand;
  HandLinkFrames(robot.hand, f, &hand);
  const Eigen::Isometry3d X_WH = arm.X_WL[kArmDof] * robot.X_FH;

  std::vector<Eigen::Isometry3d> poses;
  poses.reserve(static_cast<size_t>(ViewerLinkCount(robot)));
  poses.insert(poses.end(), arm.X_WL.begin(), arm.X_WL.end());
  poses.push_back(X_WH);
  poses.push_back(X_WH * hand.X_HP);
  for (const auto& finger : hand.X_HL) {
    for (const Eigen::Isometry3d& X_HL : finger) poses.push_back(X_WH * X_HL);
  }
  return poses;
}

std::string ViewerFrameJson(const RobotModel& robot, const ViewerState& state) {
  std::string out;
  out.reserve(64 * static_cast<size_t>(ViewerLinkCount(robot)) + 128 + state.text.size());
  out.append("{\"t\":");
  AppendNumber(state.t, &out);
  out.append(",\"links\":[");
  bool first = true;
  for (const Eigen::Isometry3d& X_WL : ViewerLinkPoses(robot, state.arm, state.hand)) {
    if (!first) out.push_back(',');
    first = false;
    AppendPose(X_WL, &out);
  }
  out.append("],\"object\":");
  AppendPose(state.X_WO, &out);
  out.append(",\"text\":");
  out.append(json(state.text).dump(-1, ' ', false, json::error_handler_t::replace));
  // a physics replay's contacts and outcome; a frame without them has neither key.
  if (!state.contacts.empty()) {
    out.append(",\"contacts\":[");
    for (size_t i = 0; i < state.contacts.size(); ++i) {
      if (i > 0) out.push_back(',');
      out.push_back('[');
      for (int k = 0; k < 3; ++k) {
        if (k > 0) out.push_back(',');
        AppendNumber(state.contacts[i][k], &out);
      }
      out.push_back(']');
    }
    out.push_back(']');
  }
  if (state.outcome) {
    out.append(",\"outcome\":{\"success\":");
    out.append(state.outcome->success ? "true" : "false");
    out.append(",\"text\":");
    out.append(json(state.outcome->text).dump(-1, ' ', false, json::error_handler_t::replace));
    out.push_back('}');
  }
  out.push_back('}');
  return out;
}

}  // namespace graspsynth::viewer
