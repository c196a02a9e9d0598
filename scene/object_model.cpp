#include "scene/object_model.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <set>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/json_reader.hpp"
#include "kinematics/types.hpp"
#include "scene/triangle_mesh.hpp"

namespace graspsynth {
namespace {

constexpr std::string_view kFormat = "graspsynth-object/1";

// Inertia of solids about their centres, shape axes (z along a cylinder's or capsule's axis).
Eigen::Matrix3d CylinderInertia(double m, double r, double h) {
  const double ixx = m * (3.0 * r * r + h * h) / 12.0;
  return Eigen::Vector3d(ixx, ixx, 0.5 * m * r * r).asDiagonal();
}

Eigen::Matrix3d BoxInertia(double m, const Eigen::Vector3d& s) {
  return Eigen::Vector3d(m * (s.y() * s.y() + s.z() * s.z()) / 12.0,
                         m * (s.x() * s.x() + s.z() * s.z()) / 12.0,
                         m * (s.x() * s.x() + s.y() * s.y()) / 12.0)
      .asDiagonal();
}

Eigen::Matrix3d SphereInertia(double m, double r) {
  return Eigen::Matrix3d::Identity() * (0.4 * m * r * r);
}

// A capsule: a cylinder of length l and two hemispheres of radius r, mass split by volume.
Eigen::Matrix3d CapsuleInertia(double m, double r, double l) {
  const double v_cyl = M_PI * r * r * l;
  const double v_ball = 4.0 / 3.0 * M_PI * r * r * r;
  const double mc = m * v_cyl / (v_cyl + v_ball);
  const double ms = m - mc;
  const double ixx =
      mc * (3.0 * r * r + l * l) / 12.0 + ms * (0.4 * r * r + 0.25 * l * l + 0.375 * l * r);
  return Eigen::Vector3d(ixx, ixx, 0.5 * mc * r * r + 0.4 * ms * r * r).asDiagonal();
}

// Parallel-axis term of a point mass m at offset d.
Eigen::Matrix3d Shift(double m, const Eigen::Vector3d& d) {
  return m * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
}

// The centre of mass of a part's solid in its shape frame, and its inertia there per kg.
struct SolidProperties {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about `centre`, shape axes, for mass m
};

SolidProperties PartSolid(const CollisionShape& s, double m) {
  SolidProperties out;
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      out.inertia = BoxInertia(m, s.size);
      break;
    case CollisionShape::Kind::kCylinder:
      out.inertia = CylinderInertia(m, s.size[0], s.size[1]);
      break;
    case CollisionShape::Kind::kCapsule:
      out.inertia = CapsuleInertia(m, s.size[0], s.size[1]);
      break;
    case CollisionShape::Kind::kSphere:
      out.inertia = SphereInertia(m, s.size[0]);
      break;
    case CollisionShape::Kind::kMesh: {
      const MeshMassProperties mp = ComputeMeshMassProperties(*s.mesh);
      out.centre = mp.centroid;
      out.inertia = (m / mp.volume) * mp.unit_inertia;
      break;
    }
  }
  return out;
}

// R = Rz(yaw) Ry(pitch) Rx(roll) from degrees; a zero angle contributes an exact identity.
Eigen::Matrix3d RotationFromRpyDeg(const Eigen::Vector3d& rpy_deg) {
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitX()};
  const double angles[3] = {rpy_deg.z(), rpy_deg.y(), rpy_deg.x()};
  bool first = true;
  for (int k = 0; k < 3; ++k) {
    if (angles[k] == 0.0) continue;
    const Eigen::Matrix3d Rk = Eigen::AngleAxisd(angles[k] * kDeg, axes[k]).toRotationMatrix();
    R = first ? Rk : Eigen::Matrix3d(R * Rk);
    first = false;
  }
  return R;
}

PartContact ParseTouches(const JsonReader& field) {
  if (!field.present()) return PartContact::kRobotAndTable;
  const std::string v = field.IsString() ? field.AsString() : std::string();
  if (v == "robot and table") return PartContact::kRobotAndTable;
  if (v == "robot") return PartContact::kRobot;
  if (v == "table") return PartContact::kTable;
  field.Fail("\"robot and table\", \"robot\" or \"table\"");
}

ObjectPart ParsePart(const JsonReader& p, double default_friction,
                     const std::filesystem::path& mesh_dir) {
  p.AsObject();
  p.RejectUnknownKeys({"name", "type", "size", "radius", "length", "file", "scale", "position",
                       "rpy_deg", "mass", "density", "friction", "touches", "comment"});
  ObjectPart part;
  part.name = p.String("name");
  if (part.name.empty()) p.Field("name").Fail("a non-empty name");
  CollisionShape& s = part.shape;
  const JsonReader type = p.Field("type");
  const std::string t = type.IsString() ? type.AsString() : std::string();
  auto allow_only = [&](std::initializer_list<std::string_view> keys) {
    for (std::string_view k : {"size", "radius", "length", "file", "scale"}) {
      if (p.Has(k) && std::find(keys.begin(), keys.end(), k) == keys.end()) {
        p.Field(k).Fail("no '" + std::string(k) + "' on a part of type \"" + t + "\"");
      }
    }
  };
  if (t == "box") {
    allow_only({"size"});
    s.kind = CollisionShape::Kind::kBox;
    s.size = p.Numbers("size", 3, 1e-4, 5.0);
  } else if (t == "cylinder" || t == "capsule") {
    allow_only({"radius", "length"});
    s.kind = t == "cylinder" ? CollisionShape::Kind::kCylinder : CollisionShape::Kind::kCapsule;
    s.size << p.NumberIn("radius", 1e-4, 2.5),
        p.NumberIn("length", t == "capsule" ? 0.0 : 1e-4, 5.0), 0.0;
  } else if (t == "sphere") {
    allow_only({"radius"});
    s.kind = CollisionShape::Kind::kSphere;
    s.size << p.NumberIn("radius", 1e-4, 2.5), 0.0, 0.0;
  } else if (t == "mesh") {
    allow_only({"file", "scale"});
    s.kind = CollisionShape::Kind::kMesh;
    const std::string file = p.String("file");
    const double scale = p.Has("scale") ? p.NumberIn("scale", 1e-6, 1e3) : 1.0;
    try {
      auto mesh = std::make_shared<TriangleMesh>(LoadTriangleMesh(mesh_dir / file, scale));
      CheckSolidMesh(*mesh);
      s.mesh = std::move(mesh);
    } catch (const InputError& e) {
      throw InputError(p.source() + ": field '" + p.path() + ".file': " + e.what());
    }
  } else {
    type.Fail("a part type: \"box\", \"cylinder\", \"capsule\", \"sphere\" or \"mesh\"");
  }
  if (p.Has("position")) s.X_LG.translation() = p.Numbers("position", 3, -5.0, 5.0);
  if (p.Has("rpy_deg"))
    s.X_LG.linear() = RotationFromRpyDeg(p.Numbers("rpy_deg", 3, -360.0, 360.0));
  part.friction = p.Has("friction") ? p.NumberIn("friction", 0.0, 10.0) : default_friction;
  part.touches = ParseTouches(p.Field("touches"));
  if (p.Has("mass") && p.Has("density"))
    p.Field("density").Fail("either a mass or a density, not both");
  if (p.Has("mass")) {
    part.mass = p.NumberIn("mass", 1e-6, 1000.0);
  } else if (p.Has("density")) {
    part.mass = p.NumberIn("density", 1.0, 25000.0) * ShapeVolume(s);
  } else if (part.touches_robot()) {
    p.Field("mass").Fail(
        "a mass in kg (or a density in kg/m^3); only a part that touches only "
        "the table may have neither");
  }
  return part;
}

}  // namespace

const HandleAxis& ObjectModel::Handle(std::string_view needed_by) const {
  if (!handle) {
    throw InputError("object '" + name + "' (" + source + ") has no handle, and " +
                     std::string(needed_by) + " needs one");
  }
  return *handle;
}

Eigen::Vector3d ObjectModel::HandleDirection(const Eigen::Isometry3d& X_WO) const {
  return X_WO.linear() * (handle ? handle->Along() : Eigen::Vector3d::UnitX());
}

ObjectInertia ObjectModel::Inertia() const {
  ObjectInertia out;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> centres;
  std::vector<SolidProperties> solids;
  for (const ObjectPart& p : parts) {
    SolidProperties solid = PartSolid(p.shape, p.mass);
    const Eigen::Vector3d c_O = p.shape.X_LG * solid.centre;
    centres.push_back(c_O);
    solids.push_back(solid);
    if (p.mass <= 0.0) continue;
    out.mass += p.mass;
    moment += p.mass * c_O;
  }
  if (out.mass <= 0.0) return out;
  out.p_OC = moment / out.mass;
  for (size_t i = 0; i < parts.size(); ++i) {
    const ObjectPart& p = parts[i];
    if (p.mass <= 0.0) continue;
    const Eigen::Matrix3d& R = p.shape.X_LG.linear();
    out.I_C += R.isIdentity(0.0) ? solids[i].inertia
                                 : Eigen::Matrix3d(R * solids[i].inertia * R.transpose());
    out.I_C += Shift(p.mass, centres[i] - out.p_OC);
  }
  return out;
}

double LowestPoint(const CollisionShape& s) {
  const Eigen::Matrix3d& R = s.X_LG.linear();
  const double z = s.X_LG.translation().z();
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      return z - (std::abs(R(2, 0)) * 0.5 * s.size.x() + std::abs(R(2, 1)) * 0.5 * s.size.y() +
                  std::abs(R(2, 2)) * 0.5 * s.size.z());
    case CollisionShape::Kind::kCylinder: {
      const double a = R(2, 2);
      return z -
             (std::abs(a) * 0.5 * s.size[1] + s.size[0] * std::sqrt(std::max(0.0, 1.0 - a * a)));
    }
    case CollisionShape::Kind::kCapsule:
      return z - (std::abs(R(2, 2)) * 0.5 * s.size[1] + s.size[0]);
    case CollisionShape::Kind::kSphere:
      return z - s.size[0];
    case CollisionShape::Kind::kMesh: {
      double lo = INFINITY;
      for (const Eigen::Vector3d& v : s.mesh->vertices) lo = std::min(lo, (s.X_LG * v).z());
      return lo;
    }
  }
  return z;
}

double ShapeVolume(const CollisionShape& s) {
  switch (s.kind) {
    case CollisionShape::Kind::kBox:
      return s.size.prod();
    case CollisionShape::Kind::kCylinder:
      return M_PI * s.size[0] * s.size[0] * s.size[1];
    case CollisionShape::Kind::kCapsule:
      return M_PI * s.size[0] * s.size[0] * (s.size[1] + 4.0 / 3.0 * s.size[0]);
    case CollisionShape::Kind::kSphere:
      return 4.0 / 3.0 * M_PI * std::pow(s.size[0], 3);
    case CollisionShape::Kind::kMesh:
      return ComputeMeshMassProperties(*s.mesh).volume;
  }
  return 0.0;
}

ObjectModel ParseObjectModel(std::string_view json_text, const std::string& source,
                             const std::filesystem::path& mesh_dir) {
  const JsonReader top = JsonReader::Parse(json_text, source).AsObject();
  top.ExpectString("format", kFormat);
  top.RejectUnknownKeys(
      {"format", "name", "comment", "sources", "friction", "parts", "handle", "paper_object"});
  ObjectModel o;
  o.source = source;
  o.name = top.String("name");
  if (o.name.empty()) top.Field("name").Fail("a non-empty name");
  if (top.Has("friction")) o.friction = top.NumberIn("friction", 0.0, 10.0);
  if (top.Has("paper_object")) o.paper_object = top.Bool("paper_object");
  const std::vector<JsonReader> parts = top.Array("parts");
  if (parts.empty()) top.Field("parts").Fail("at least one part");
  std::set<std::string> names;
  for (const JsonReader& p : parts) {
    o.parts.push_back(ParsePart(p, o.friction, mesh_dir));
    if (!names.insert(o.parts.back().name).second) {
      p.Field("name").Fail("a name no other part has");
    }
  }
  double lowest = INFINITY;
  bool massive = false;
  for (const ObjectPart& p : o.parts) {
    if (p.touches != PartContact::kRobot) lowest = std::min(lowest, LowestPoint(p.shape));
    massive = massive || p.mass > 0.0;
  }
  if (!massive) top.Field("parts").Fail("at least one part with a mass or a density");
  if (!std::isfinite(lowest)) {
    top.Field("parts").Fail("at least one part that touches the table (the object rests on it)");
  }
  if (!(lowest < 0.0)) {
    top.Field("parts").Fail(
        "parts whose lowest point is below the object frame's origin (O is "
        "the object centre; the lowest point is " +
        std::to_string(lowest) + " m)");
  }
  o.rest_height = -lowest;
  if (top.Has("handle")) {
    const JsonReader h = top.Object("handle");
    h.RejectUnknownKeys({"start_radius", "end_radius", "axis_height", "direction_deg", "comment"});
    HandleAxis a;
    a.start_radius = h.NumberIn("start_radius", -5.0, 5.0);
    a.end_radius = h.NumberIn("end_radius", -5.0, 5.0);
    a.axis_height = h.NumberIn("axis_height", 0.0, 5.0);
    if (h.Has("direction_deg")) a.direction = h.NumberIn("direction_deg", -360.0, 360.0) * kDeg;
    if (a.end_radius <= a.start_radius) h.Field("end_radius").Fail("a radius above start_radius");
    o.handle = a;
  }
  return o;
}

ObjectModel LoadObjectModel(const std::filesystem::path& path) {
  return ParseObjectModel(ReadInputFile(path, input_kind::kObject), path.string(),
                          path.parent_path());
}

std::filesystem::path DefaultObjectDirectory() { return DataDirectory() / "models" / "objects"; }

std::filesystem::path ResolveObjectPath(const std::string& name_or_file) {
  namespace fs = std::filesystem;
  const fs::path as_file(name_or_file);
  std::error_code ec;
  if (fs::is_regular_file(as_file, ec) || as_file.extension() == ".json" ||
      name_or_file.find('/') != std::string::npos) {
    return as_file;
  }
  const fs::path shipped = DefaultObjectDirectory() / (name_or_file + ".json");
  if (fs::is_regular_file(shipped, ec)) return shipped;
  std::string known;
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(DefaultObjectDirectory(), ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError("unknown object '" + name_or_file + "': not a file, and not a shipped object (" +
                   (known.empty() ? std::string("none found") : known) + " in " +
                   DefaultObjectDirectory().string() + ")");
}

}  // namespace graspsynth
