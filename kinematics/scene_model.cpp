#include "kinematics/scene_model.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/data_dir.hpp"
#include "common/errors.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

constexpr std::string_view kFormat = "graspsynth-scene/1";

// Reads typed fields of one JSON object, naming "source: section.field" in every error.
class FieldReader {
 public:
  FieldReader(const json& object, std::string where) : object_(object), where_(std::move(where)) {
    if (!object_.is_object()) throw InputError(where_ + " must be a JSON object");
  }

  const json& Get(const std::string& key) const {
    const auto it = object_.find(key);
    if (it == object_.end()) throw InputError(where_ + "." + key + " is missing");
    return *it;
  }

  double Number(const std::string& key, double min, double max) const {
    const json& v = Get(key);
    if (!v.is_number()) throw Bad(key, v, "is not a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < min || x > max) {
      std::ostringstream range;
      range << "is outside [" << min << ", " << max << "]";
      throw Bad(key, v, range.str());
    }
    return x;
  }

  template <int N>
  Eigen::Matrix<double, N, 1> Vector(const std::string& key, double min, double max) const {
    const json& v = Get(key);
    if (!v.is_array() || v.size() != N) {
      throw Bad(key, v, "is not an array of " + std::to_string(N) + " numbers");
    }
    Eigen::Matrix<double, N, 1> out;
    for (int i = 0; i < N; ++i) {
      if (!v[i].is_number() || !std::isfinite(v[i].get<double>()) || v[i].get<double>() < min ||
          v[i].get<double>() > max) {
        throw Bad(key, v, "has an entry that is not a number in the allowed range");
      }
      out[i] = v[i].get<double>();
    }
    return out;
  }

  std::string String(const std::string& key) const {
    const json& v = Get(key);
    if (!v.is_string()) throw Bad(key, v, "is not a string");
    return v.get<std::string>();
  }

  FieldReader Section(const std::string& key) const { return {Get(key), where_ + "." + key}; }

 private:
  InputError Bad(const std::string& key, const json& v, const std::string& why) const {
    return InputError(where_ + "." + key + " = " + v.dump() + " " + why);
  }

  const json& object_;
  std::string where_;
};

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
  json root;
  try {
    root = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw InputError(source + ": not valid JSON: " + e.what());
  }
  const FieldReader top(root, source);
  const std::string format = top.String("format");
  if (format != kFormat) {
    throw InputError(source + ".format = \"" + format + "\" is not " + std::string(kFormat));
  }
  SceneModel scene;
  scene.source = source;

  const FieldReader table = top.Section("table");
  scene.table.top_z = table.Number("top_z", -2.0, 2.0);
  scene.table.centre_xy = table.Vector<2>("centre_xy", -5.0, 5.0);
  scene.table.size = table.Vector<3>("size", 1e-3, 10.0);
  scene.table.friction = table.Number("friction", 0.0, 10.0);

  const FieldReader obj = top.Section("object");
  ObjectModel& o = scene.object;
  o.name = obj.String("name");
  o.centre_xy = obj.Vector<2>("centre", -5.0, 5.0);
  o.handle_offset = obj.Number("handle_offset_deg", -360.0, 360.0) * M_PI / 180.0;
  o.body_radius = obj.Number("body_radius", 1e-3, 1.0);
  o.body_height = obj.Number("body_height", 1e-3, 1.0);
  o.handle_start_radius = obj.Number("handle_start_radius", 0.0, 2.0);
  o.handle_end_radius = obj.Number("handle_end_radius", 1e-3, 2.0);
  o.handle_width = obj.Number("handle_width", 1e-3, 0.5);
  o.handle_thickness = obj.Number("handle_thickness", 1e-3, 0.5);
  o.handle_axis_height = obj.Number("handle_axis_height", 0.0, 1.0);
  o.body_mass = obj.Number("body_mass", 1e-3, 100.0);
  o.handle_mass = obj.Number("handle_mass", 1e-3, 100.0);
  o.friction = obj.Number("friction", 0.0, 10.0);
  if (o.handle_end_radius <= o.handle_start_radius) {
    throw InputError(source + ".object.handle_end_radius must exceed handle_start_radius");
  }
  if (o.handle_axis_height < 0.5 * o.handle_thickness) {
    throw InputError(source + ".object.handle_axis_height puts the handle into the table");
  }

  const FieldReader region = top.Section("grasp_region");
  const std::string shape = region.String("shape");
  if (shape == "cylinder") {
    scene.grasp_region.shape = GraspRegionModel::Shape::kCylinder;
  } else if (shape == "sphere") {
    scene.grasp_region.shape = GraspRegionModel::Shape::kSphere;
  } else {
    throw InputError(source + ".grasp_region.shape = \"" + shape +
                     "\" is neither \"cylinder\" nor \"sphere\"");
  }
  scene.grasp_region.radius = region.Number("radius", 1e-3, 5.0);
  scene.grasp_region.height = region.Number("height", 1e-3, 10.0);
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
