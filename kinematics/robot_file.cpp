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

std::vector<std::string> NonEmptyStrings(const JsonReader& array) {
  const std::vector<JsonReader> items = array.AsArray();
  if (items.empty()) array.Fail("a non-empty array of non-empty strings");
  std::vector<std::string> out;
  for (const JsonReader& item : items) {
    if (!item.IsString() || item.AsString().empty()) item.Fail("a non-empty string");
    if (std::find(out.begin(), out.end(), item.AsString()) != out.end()) {
      item.Fail("a name not listed before in " + array.path());
    }
    out.push_back(item.AsString());
  }
  return out;
}

RobotFileCoupling ReadCoupling(const JsonReader& c, const std::vector<std::string>& joints) {
  c.AsObject();
  c.RejectUnknownKeys({"joint", "follows", "ratio", "offset"});
  RobotFileCoupling out;
  out.joint = NonEmptyString(c, "joint");
  if (std::find(joints.begin(), joints.end(), out.joint) == joints.end()) {
    c.Field("joint").Fail("one of the finger's joints");
  }
  out.follows = NonEmptyString(c, "follows");
  if (out.follows == out.joint) c.Field("follows").Fail("a joint other than its 'joint'");
  if (c.Has("ratio")) out.ratio = c.Number("ratio");
  if (c.Has("offset")) out.offset = c.Number("offset");
  return out;
}

RobotFileFinger ReadFinger(const JsonReader& f) {
  f.AsObject();
  f.RejectUnknownKeys({"name", "role", "joints", "tip_link", "coupled"});
  RobotFileFinger out;
  out.name = NonEmptyString(f, "name");
  if (f.Has("role")) {
    f.ExpectString("role", "thumb");
    out.role = "thumb";
  }
  out.joints = NonEmptyStrings(f.Field("joints"));
  out.tip_link = NonEmptyString(f, "tip_link");
  if (f.Has("coupled")) {
    for (const JsonReader& c : f.Field("coupled").AsArray()) {
      out.coupled.push_back(ReadCoupling(c, out.joints));
      for (size_t k = 0; k + 1 < out.coupled.size(); ++k) {
        if (out.coupled[k].joint == out.coupled.back().joint) {
          c.Field("joint").Fail("a joint not coupled before");
        }
      }
    }
  }
  return out;
}

RobotFileHand ReadHand(const JsonReader& hand) {
  hand.AsObject();
  hand.RejectUnknownKeys({"mount_link", "palm_link", "palm_frame", "fingers", "servo"});
  RobotFileHand out;
  out.mount_link = NonEmptyString(hand, "mount_link");
  out.palm_link = NonEmptyString(hand, "palm_link");
  if (out.palm_link == out.mount_link) {
    hand.Field("palm_link").Fail("a link other than hand.mount_link");
  }
  if (hand.Has("palm_frame")) hand.ExpectString("palm_frame", "gifu");
  const JsonReader fingers = hand.Field("fingers");
  const std::vector<JsonReader> items = fingers.AsArray();
  if (items.empty()) fingers.Fail("a non-empty array of fingers");
  bool thumb = false;
  for (const JsonReader& f : items) {
    out.fingers.push_back(ReadFinger(f));
    const RobotFileFinger& finger = out.fingers.back();
    for (size_t k = 0; k + 1 < out.fingers.size(); ++k) {
      if (out.fingers[k].name == finger.name) f.Field("name").Fail("a name no finger has before");
    }
    if (!finger.role.empty() && std::exchange(thumb, true)) {
      f.Field("role").Fail("one thumb (another finger is the thumb)");
    }
  }
  if (hand.Has("servo")) out.servo = ReadServo(hand.Field("servo"));
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
  if (top.Has("hand")) file.hand = ReadHand(top.Field("hand"));
  file.grasp = top.OptionalField("grasp");
  return file;
}

RobotFile LoadRobotFile(const std::filesystem::path& path) {
  return ParseRobotFile(ReadInputFile(path, kRobotFileKind), path.string(), path.parent_path());
}

ArmModel LoadArmFromRobotFile(const std::filesystem::path& path) {
  return ArmFromRobotFile(LoadRobotFile(path));
}

namespace {

ArmChainNames ArmNames(const RobotFile& file) {
  ArmChainNames names;
  names.base_link = file.arm.base_link;
  names.flange_link = file.arm.flange_link;
  names.base_where = file.source + ": field 'arm.base_link'";
  names.flange_where = file.source + ": field 'arm.flange_link'";
  names.chain_where = file.source + ": fields 'arm.base_link', 'arm.flange_link'";
  return names;
}

HandNames HandPartNames(const RobotFile& file) {
  const RobotFileHand& hand = *file.hand;
  const std::string field = file.source + ": field 'hand.";
  HandNames names;
  names.mount_link = hand.mount_link;
  names.palm_link = hand.palm_link;
  names.mount_where = field + "mount_link'";
  names.palm_where = field + "palm_link'";
  names.where = file.source + ": field 'hand'";
  for (size_t i = 0; i < hand.fingers.size(); ++i) {
    const RobotFileFinger& f = hand.fingers[i];
    const std::string at = field + "fingers[" + std::to_string(i) + "]";
    FingerPartNames finger;
    finger.name = f.name;
    finger.joints = f.joints;
    finger.tip_link = f.tip_link;
    finger.where = at + "'";
    finger.tip_where = at + ".tip_link'";
    for (size_t k = 0; k < f.joints.size(); ++k) {
      finger.joints_where.push_back(at + ".joints[" + std::to_string(k) + "]'");
    }
    for (size_t k = 0; k < f.coupled.size(); ++k) {
      const RobotFileCoupling& c = f.coupled[k];
      finger.coupled.push_back(
          {c.joint, c.follows, c.ratio, c.offset, at + ".coupled[" + std::to_string(k) + "]'"});
    }
    names.fingers.push_back(std::move(finger));
  }
  return names;
}

// The arm of `chain` (the robot file's arm.base_link .. arm.flange_link of its URDF).
ArmModel ArmOfChain(const RobotFile& file, ArmChain chain) {
  const std::string urdf = file.urdf.string();
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

}  // namespace

ArmModel ArmFromRobotFile(const RobotFile& file) {
  return ArmOfChain(file, ReadArmChain(ReadInputFile(file.urdf, input_kind::kRobot),
                                       file.urdf.string(), ArmNames(file)));
}

RobotModel RobotFromFile(const RobotFile& file) {
  if (!file.hand) {
    throw InputError(file.source +
                     ": field 'hand': expected an object (the whole robot needs its hand), found "
                     "nothing");
  }
  const std::string urdf = file.urdf.string();
  RobotParts parts = ReadRobotParts(ReadInputFile(file.urdf, input_kind::kRobot), urdf,
                                    ArmNames(file), HandPartNames(file));
  ArmModel arm = ArmOfChain(file, std::move(parts.arm));
  RobotModel robot = [&] {
    try {
      HandModel hand(urdf, std::move(parts.mount), std::move(parts.palm), parts.X_HP,
                     std::move(parts.fingers));
      return RobotModel{file.source, std::move(arm), parts.X_FH, std::move(hand),
                        file.name,   file.X_WB,      {}};
    } catch (const InputError& e) {
      throw InputError(file.source +
                       ": field 'hand.fingers': expected a hand graspsynth can use, "
                       "found " +
                       e.what());
    }
  }();
  // the scripted grasp's part names the hand's joints: read against the hand.
  if (file.grasp) robot.grasp = ReadRobotGrasp(*file.grasp, robot.hand);
  return robot;
}

RobotModel LoadRobot(const std::filesystem::path& path) {
  if (path.extension() != ".json") return LoadRobotModel(path);
  return RobotFromFile(LoadRobotFile(path));
}

RobotModel LoadRobotOption(std::string_view name_or_path) {
  if (name_or_path.empty()) return LoadRobotModel(DefaultRobotDescriptionPath());
  return LoadRobot(ResolveRobotPath(name_or_path));
}

void RequireDefaultRobot(const RobotModel& robot, std::string_view user, std::string_view data) {
  if (robot.name == kDefaultRobotName) return;
  throw InputError(std::string(user) + " cannot use robot '" + robot.name + "' (" + robot.source +
                   ") yet: it reads " + std::string(data) +
                   ", made for the PA-10 + Gifu Hand III (" + std::string(kDefaultRobotName) + ")");
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
