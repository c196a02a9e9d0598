#include "scene/scene_model.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <sstream>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/json_reader.hpp"

namespace graspsynth {
namespace {

constexpr std::string_view kFormat = "graspsynth-scene/2";
constexpr std::string_view kFormatV1 = "graspsynth-scene/1";

// The inline pan of graspsynth-scene/1.
ObjectModel ParseLegacyPan(const JsonReader& obj) {
  LegacyPanParameters p;
  p.body_radius = obj.NumberIn("body_radius", 1e-3, 1.0);
  p.body_height = obj.NumberIn("body_height", 1e-3, 1.0);
  p.handle_start_radius = obj.NumberIn("handle_start_radius", 0.0, 2.0);
  p.handle_end_radius = obj.NumberIn("handle_end_radius", 1e-3, 2.0);
  p.handle_width = obj.NumberIn("handle_width", 1e-3, 0.5);
  p.handle_thickness = obj.NumberIn("handle_thickness", 1e-3, 0.5);
  p.handle_axis_height = obj.NumberIn("handle_axis_height", 0.0, 1.0);
  p.body_mass = obj.NumberIn("body_mass", 1e-3, 100.0);
  p.handle_mass = obj.NumberIn("handle_mass", 1e-3, 100.0);
  p.friction = obj.NumberIn("friction", 0.0, 10.0);
  if (p.handle_end_radius <= p.handle_start_radius) {
    obj.Field("handle_end_radius").Fail("a radius above handle_start_radius");
  }
  if (p.handle_axis_height < 0.5 * p.handle_thickness) {
    obj.Field("handle_axis_height")
        .Fail("at least half the handle_thickness (the handle would be in the table)");
  }
  return LegacyPanObject(obj.String("name"), p, obj.source());
}

}  // namespace

ObjectModel LegacyPanObject(const std::string& name, const LegacyPanParameters& p,
                            const std::string& source) {
  ObjectModel o;
  o.name = name;
  o.source = source;
  o.friction = p.friction;
  o.rest_height = 0.5 * p.body_height;
  o.paper_object = true;  // scene/1 held the study's pan inline
  ObjectPart body;
  body.name = "body";
  body.shape.kind = CollisionShape::Kind::kCylinder;
  body.shape.size << p.body_radius, p.body_height, 0.0;
  body.mass = p.body_mass;
  body.friction = p.friction;
  body.touches = PartContact::kRobot;
  ObjectPart handle;
  handle.name = "handle";
  handle.shape.kind = CollisionShape::Kind::kBox;
  handle.shape.size << p.handle_end_radius - p.handle_start_radius, p.handle_width,
      p.handle_thickness;
  handle.shape.X_LG.translation() << 0.5 * (p.handle_start_radius + p.handle_end_radius), 0.0,
      p.handle_axis_height - o.rest_height;
  handle.mass = p.handle_mass;
  handle.friction = p.friction;
  ObjectPart foot;
  foot.name = "foot";
  const double side = std::sqrt(2.0) * p.body_radius;
  foot.shape.size = Eigen::Vector3d(side, side, p.body_height);
  foot.friction = p.friction;
  foot.touches = PartContact::kTable;
  ObjectPart foot_turned = foot;
  foot_turned.name = "foot_turned";
  foot_turned.shape.X_LG.linear() =
      Eigen::AngleAxisd(M_PI / 4, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  o.parts = {body, handle, foot, foot_turned};
  o.handle = HandleAxis{p.handle_start_radius, p.handle_end_radius, p.handle_axis_height};
  return o;
}

Eigen::Isometry3d SceneModel::ObjectPose(const Placement& placement) const {
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << CentreXY(placement), table.top_z + object.rest_height;
  X_WO.rotate(Eigen::AngleAxisd(placement.theta + object_yaw_offset, Eigen::Vector3d::UnitZ()));
  return X_WO;
}

void SceneModel::CheckOnTable(const Eigen::Vector2d& xy) const {
  const Eigen::Vector2d lo = table.centre_xy - 0.5 * table.size.head<2>();
  const Eigen::Vector2d hi = table.centre_xy + 0.5 * table.size.head<2>();
  if (xy.allFinite() && (xy.array() >= lo.array()).all() && (xy.array() <= hi.array()).all()) {
    return;
  }
  std::ostringstream why;
  why << "the object centre (" << xy.x() << ", " << xy.y() << ") m is not on the table of "
      << source << " (x " << lo.x() << " to " << hi.x() << " m, y " << lo.y() << " to " << hi.y()
      << " m)";
  throw InputError(why.str());
}

SceneModel ParseSceneModel(std::string_view json_text, const std::string& source,
                           const std::filesystem::path& base_dir,
                           const std::string& object_override) {
  const JsonReader top = JsonReader::Parse(json_text, source).AsObject();
  const JsonReader format = top.Field("format");
  const bool v1 = format.IsString() && format.AsString() == kFormatV1;
  if (!v1) top.ExpectString("format", kFormat);
  SceneModel scene;
  scene.source = source;

  const JsonReader table = top.Object("table");
  scene.table.top_z = table.NumberIn("top_z", -2.0, 2.0);
  scene.table.centre_xy = table.Numbers("centre_xy", 2, -5.0, 5.0);
  scene.table.size = table.Numbers("size", 3, 1e-3, 10.0);
  scene.table.friction = table.NumberIn("friction", 0.0, 10.0);

  if (v1) {
    const JsonReader obj = top.Object("object");
    scene.object_centre_xy = obj.Numbers("centre", 2, -5.0, 5.0);
    scene.object_yaw_offset = Radians(obj.NumberIn("handle_offset_deg", -360.0, 360.0));
    if (object_override.empty()) scene.object = ParseLegacyPan(obj);
  } else {
    scene.object_centre_xy = top.Numbers("object_centre", 2, -5.0, 5.0);
    scene.object_yaw_offset = Radians(top.NumberIn("object_yaw_offset_deg", -360.0, 360.0));
    const std::string file = top.String("object");
    if (object_override.empty()) {
      try {
        scene.object = LoadObjectModel(base_dir / file);
      } catch (const InputError& e) {
        throw InputError(source + ": field 'object': " + e.what());
      }
    }
  }
  if (!object_override.empty()) scene.object = LoadObjectModel(ResolveObjectPath(object_override));

  const JsonReader region = top.Object("grasp_region");
  const JsonReader shape = region.Field("shape");
  const std::string shape_name = shape.IsString() ? shape.AsString() : std::string();
  if (shape_name == "cylinder") {
    scene.grasp_region.shape = GraspRegionModel::Shape::kCylinder;
  } else if (shape_name == "sphere") {
    scene.grasp_region.shape = GraspRegionModel::Shape::kSphere;
  } else {
    shape.Fail("\"cylinder\" or \"sphere\"");
  }
  scene.grasp_region.radius = region.NumberIn("radius", 1e-3, 5.0);
  scene.grasp_region.height = region.NumberIn("height", 1e-3, 10.0);
  return scene;
}

SceneModel LoadSceneModel(const std::filesystem::path& path, const std::string& object_override) {
  return ParseSceneModel(ReadInputFile(path, input_kind::kScene), path.string(), path.parent_path(),
                         object_override);
}

std::filesystem::path DefaultSceneModelPath() { return DataDirectory() / "models" / "scene.json"; }

}  // namespace graspsynth
