#include "kinematics/scene_model.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"

namespace graspsynth {
namespace {

constexpr std::string_view kFormat = "graspsynth-scene/1";

}  // namespace

CollisionShape ObjectModel::BodyShape() const {
  CollisionShape body;
  body.kind = CollisionShape::Kind::kCylinder;
  body.size << body_radius, body_height, 0.0;
  return body;
}

CollisionShape ObjectModel::HandleShape() const {
  CollisionShape handle;
  handle.kind = CollisionShape::Kind::kBox;
  handle.size << handle_end_radius - handle_start_radius, handle_width, handle_thickness;
  handle.X_LG.translation() << 0.5 * (handle_start_radius + handle_end_radius), 0.0,
      handle_axis_height - rest_height();
  return handle;
}

Eigen::Isometry3d SceneModel::ObjectPose(double theta) const {
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  X_WO.translation() << object.centre_xy, table.top_z + object.rest_height();
  X_WO.rotate(Eigen::AngleAxisd(theta + object.handle_offset, Eigen::Vector3d::UnitZ()));
  return X_WO;
}

SceneModel ParseSceneModel(std::string_view json_text, const std::string& source) {
  const JsonReader top = JsonReader::Parse(json_text, source).AsObject();
  top.ExpectString("format", kFormat);
  SceneModel scene;
  scene.source = source;

  const JsonReader table = top.Object("table");
  scene.table.top_z = table.NumberIn("top_z", -2.0, 2.0);
  scene.table.centre_xy = table.Numbers("centre_xy", 2, -5.0, 5.0);
  scene.table.size = table.Numbers("size", 3, 1e-3, 10.0);
  scene.table.friction = table.NumberIn("friction", 0.0, 10.0);

  const JsonReader obj = top.Object("object");
  ObjectModel& o = scene.object;
  o.name = obj.String("name");
  o.centre_xy = obj.Numbers("centre", 2, -5.0, 5.0);
  o.handle_offset = obj.NumberIn("handle_offset_deg", -360.0, 360.0) * M_PI / 180.0;
  o.body_radius = obj.NumberIn("body_radius", 1e-3, 1.0);
  o.body_height = obj.NumberIn("body_height", 1e-3, 1.0);
  o.handle_start_radius = obj.NumberIn("handle_start_radius", 0.0, 2.0);
  o.handle_end_radius = obj.NumberIn("handle_end_radius", 1e-3, 2.0);
  o.handle_width = obj.NumberIn("handle_width", 1e-3, 0.5);
  o.handle_thickness = obj.NumberIn("handle_thickness", 1e-3, 0.5);
  o.handle_axis_height = obj.NumberIn("handle_axis_height", 0.0, 1.0);
  o.body_mass = obj.NumberIn("body_mass", 1e-3, 100.0);
  o.handle_mass = obj.NumberIn("handle_mass", 1e-3, 100.0);
  o.friction = obj.NumberIn("friction", 0.0, 10.0);
  if (o.handle_end_radius <= o.handle_start_radius) {
    obj.Field("handle_end_radius").Fail("a radius above handle_start_radius");
  }
  if (o.handle_axis_height < 0.5 * o.handle_thickness) {
    obj.Field("handle_axis_height")
        .Fail("at least half the handle_thickness (the handle would be in the table)");
  }

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

SceneModel LoadSceneModel(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open scene description '" + path.string() + "'");
  std::stringstream text;
  text << in.rdbuf();
  return ParseSceneModel(text.str(), path.string());
}

std::filesystem::path DefaultSceneModelPath() { return DataDirectory() / "models" / "scene.json"; }

}  // namespace graspsynth
