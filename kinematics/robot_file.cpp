#include "kinematics/robot_file.hpp"

#include <algorithm>
#include <sstream>
#include <system_error>
#include <utility>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/json_reader.hpp"
#include "kinematics/types.hpp"
#include "kinematics/urdf_arm_chain.hpp"

namespace graspsynth {
namespace {

constexpr std::string_view kFormat = "graspsynth-robot/1";
// a robot file is a small JSON file; it is read with the limit of every JSON input.
constexpr InputFileKind kRobotFileKind{"robot file", input_kind::kJsonBytes};

std::string NonEmptyString(const JsonReader& top, std::string_view key) {
  const JsonReader field = top.Field(key);
  if (!field.IsString() || field.AsString().empty()) field.Fail("a non-empty string");
  return field.AsString();
}

RobotFileServo ReadServo(const JsonReader& servo) {
  servo.AsObject();
  servo.RejectUnknownKeys({"position_gain", "force_cap_scale"});
  RobotFileServo out;
  if (servo.Has("position_gain")) out.position_gain = servo.PositiveNumber("position_gain");
  if (servo.Has("force_cap_scale")) out.force_cap_scale = servo.PositiveNumber("force_cap_scale");
  return out;
}

RobotFileArm ReadArm(const JsonReader& arm) {
  arm.AsObject();
  arm.RejectUnknownKeys({"base_link", "flange_link", "ik", "srs_tolerance_m", "servo"});
  RobotFileArm out;
  out.base_link = NonEmptyString(arm, "base_link");
  out.flange_link = NonEmptyString(arm, "flange_link");
  if (out.flange_link == out.base_link) {
    arm.Field("flange_link").Fail("a link other than arm.base_link");
  }
  arm.ExpectString("ik", "srs");
  out.ik = "srs";
  if (arm.Has("srs_tolerance_m")) {
    const JsonReader tol = arm.Field("srs_tolerance_m");
    out.srs_tolerance_m = tol.AsNumber();
    if (!(out.srs_tolerance_m > 0.0 && out.srs_tolerance_m <= 0.01)) {
      tol.Fail("a tolerance in (0, 0.01] m");
    }
  }
  if (arm.Has("servo")) out.servo = ReadServo(arm.Field("servo"));
  return out;
}

// the base's pose in the world: {"position_m": [x, y, z], "yaw_deg": a}.
Eigen::Isometry3d ReadBase(const JsonReader& base) {
  base.AsObject();
  base.RejectUnknownKeys({"position_m", "yaw_deg"});
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.translation() = base.Field("position_m").AsNumbers(3, -10.0, 10.0);
  const double yaw_deg = base.Has("yaw_deg") ? base.NumberIn("yaw_deg", -180.0, 180.0) : 0.0;
  X_WB.linear() = Eigen::AngleAxisd(Radians(yaw_deg), Eigen::Vector3d::UnitZ()).matrix();
  return X_WB;
}

}  // namespace

RobotFile ParseRobotFile(std::string_view json, const std::string& source,
                         const std::filesystem::path& folder) {
  const JsonReader top = JsonReader::Parse(json, source);
  top.AsObject();
  top.ExpectString("format", kFormat);
  top.RejectUnknownKeys(
      {"format", "name", "comment", "urdf", "base", "arm", "hand", "collision", "glove", "grasp"});
  RobotFile file;
  file.source = source;
  file.name = NonEmptyString(top, "name");
  if (top.Has("comment")) file.comment = top.String("comment");
  file.urdf = folder / NonEmptyString(top, "urdf");
  if (top.Has("base")) file.X_WB = ReadBase(top.Field("base"));
  file.arm = ReadArm(top.Object("arm"));
  return file;
}

RobotFile LoadRobotFile(const std::filesystem::path& path) {
  return ParseRobotFile(ReadInputFile(path, kRobotFileKind), path.string(), path.parent_path());
}

ArmModel LoadArmFromRobotFile(const std::filesystem::path& path) {
  return ArmFromRobotFile(LoadRobotFile(path));
}

ArmModel ArmFromRobotFile(const RobotFile& file) {
  const std::string urdf = file.urdf.string();
  ArmChainNames names;
  names.base_link = file.arm.base_link;
  names.flange_link = file.arm.flange_link;
  names.base_where = file.source + ": field 'arm.base_link'";
  names.flange_where = file.source + ": field 'arm.flange_link'";
  names.chain_where = file.source + ": fields 'arm.base_link', 'arm.flange_link'";
  ArmChain chain = ReadArmChain(ReadInputFile(file.urdf, input_kind::kRobot), urdf, names);
  ArmChainOptions options;
  options.X_7F = chain.X_7F;
  options.srs_tolerance_m = file.arm.srs_tolerance_m;
  try {
    return ArmModel(urdf, std::move(chain.base), std::move(chain.joints), std::move(chain.links),
                    options);
  } catch (const InputError& e) {
    std::ostringstream msg;
    msg << file.source << ": field 'arm.ik': expected an SRS arm on the DH table of "
        << "reference/robot.md 1.3 within arm.srs_tolerance_m " << options.srs_tolerance_m
        << " m, found " << e.what();
    throw InputError(msg.str());
  }
}

std::vector<ShippedRobot> ShippedRobots() {
  constexpr std::string_view kSuffix = ".robot.json";
  const std::filesystem::path models = DataDirectory() / "models";
  std::error_code error;
  std::filesystem::directory_iterator it(models, error);
  if (error) {
    throw InputError(models.string() + ": cannot list the shipped robots: " + error.message());
  }
  std::vector<ShippedRobot> robots;
  for (const std::filesystem::directory_entry& entry : it) {
    const std::string file_name = entry.path().filename().string();
    if (file_name.size() <= kSuffix.size() || !file_name.ends_with(kSuffix)) continue;
    const std::string stem = file_name.substr(0, file_name.size() - kSuffix.size());
    const RobotFile file = LoadRobotFile(entry.path());
    if (file.name != stem) {
      throw InputError(file.source + ": field 'name': expected \"" + stem +
                       "\" (the file's name), found \"" + file.name + "\"");
    }
    robots.push_back({file.name, entry.path(), file.comment});
  }
  std::sort(robots.begin(), robots.end(),
            [](const ShippedRobot& a, const ShippedRobot& b) { return a.name < b.name; });
  return robots;
}

std::filesystem::path ResolveRobotPath(std::string_view name_or_path) {
  const std::string text(name_or_path);
  if (text.find('/') != std::string::npos || text.ends_with(".json") || text.ends_with(".urdf")) {
    return text;
  }
  const std::vector<ShippedRobot> robots = ShippedRobots();
  std::string names;
  for (const ShippedRobot& robot : robots) {
    if (robot.name == text) return robot.file;
    names += (names.empty() ? "" : ", ") + robot.name;
  }
  throw InputError("--robot: expected a shipped robot (" + names +
                   "; 'graspsynth robots' lists them) or a robot file's path, found \"" + text +
                   "\"");
}

}  // namespace graspsynth
