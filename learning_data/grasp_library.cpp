#include "learning_data/grasp_library.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string_view>

#include "common/atomic_file.hpp"
#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/field_text.hpp"
#include "common/json_reader.hpp"
#include "kinematics/pose_math.hpp"
#include "learning_data/demo_directory.hpp"
#include "learning_data/learning_data_fields.hpp"

namespace graspsynth {
namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kLibraryFormat = "graspsynth-library/1";
constexpr std::string_view kLibraryFormatV2 = "graspsynth-library/2";
// two object positions closer than this are one, m.
constexpr double kSamePosition = 1e-9;
// a quaternion read from a library may be off unit by this much (rounding by other writers);
// it is then normalized, so that the motion passes IsWellFormed (1e-9).
constexpr double kQuaternionTolerance = 1e-6;
// theta_rad of a motion must agree with its entry's theta_deg this closely, rad.
constexpr double kThetaTolerance = 1e-9;

json Vector(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

json MotionJson(const GraspingMotion& motion) {
  json waypoints = json::array();
  for (const MotionWaypoint& w : motion.waypoints) {
    const Eigen::Quaterniond q = CanonicalForFile(w.q_WH);
    waypoints.push_back({{"t", w.t},
                         {"position", Vector(w.p_WH)},
                         {"quaternion", {q.w(), q.x(), q.y(), q.z()}},
                         {"fingers", Vector(w.f)}});
  }
  return {{"theta_rad", motion.theta},
          {"object_position", Vector(motion.p_WO)},
          {"source", motion.source},
          {"waypoints", waypoints}};
}

json PlacementJson(const Eigen::Vector2d& xy, double theta_deg) {
  return {{"x", xy.x()}, {"y", xy.y()}, {"theta_deg", theta_deg}};
}

json LibraryJson(const GraspLibrary& library) {
  const bool v2 = library.HasPositions();
  json scores = json::array();
  for (const DemoScore& s : library.scores) {
    const json fields = FieldsJson<json>(s);
    if (!v2) {
      scores.push_back(fields);
      continue;
    }
    json score;  // version 2: the placement after theta_deg
    for (const auto& [key, value] : fields.items()) {
      score[key] = value;
      if (key == "theta_deg") score["placement"] = PlacementJson(s.xy, s.theta_deg);
    }
    scores.push_back(std::move(score));
  }
  json entries = json::array();
  for (const LibraryEntry& e : library.entries) {
    entries.push_back({{"theta_deg", e.theta_deg}});
    if (v2) entries.back()["placement"] = PlacementJson(e.motion.p_WO.head<2>(), e.theta_deg);
    entries.back().update(json{{"file", e.file},
                               {"trial", e.trial},
                               {"score", e.score},
                               {"lift_height", e.lift_height},
                               {"lift_duration", e.lift_duration},
                               {"motion", MotionJson(e.motion)}});
  }
  json j;
  j["format"] = v2 ? kLibraryFormatV2 : kLibraryFormat;
  j["demo_directory"] = library.demo_directory;
  j["seed"] = library.seed;
  j["perturbations"] = library.perturbations;
  j["tie_rule"] = library.tie_rule;
  j["scores"] = scores;
  j["entries"] = entries;
  return j;
}

std::string Shown(double x) { return json(x).dump(); }

double Probability(const JsonReader& object, std::string_view key) {
  return object.NumberIn(key, 0.0, 1.0);
}

MotionWaypoint ReadWaypoint(const JsonReader& object) {
  MotionWaypoint w;
  w.t = object.Number("t");
  w.p_WH = object.Vector3("position");
  w.q_WH = object.UnitQuaternion("quaternion", kQuaternionTolerance);
  if (std::abs(w.q_WH.norm() - 1.0) > 1e-15) w.q_WH.normalize();
  w.f = object.Numbers("fingers", kHandDof);
  return w;
}

GraspingMotion ReadMotion(const JsonReader& object, double theta_deg) {
  object.AsObject();
  GraspingMotion motion;
  motion.theta = object.Number("theta_rad");
  if (std::abs(motion.theta - theta_deg * kDeg) > kThetaTolerance) {
    object.Field("theta_rad").Fail("the entry's theta_deg " + Shown(theta_deg) + " in rad");
  }
  motion.p_WO = object.Vector3("object_position");
  motion.source = object.String("source");
  for (const JsonReader& waypoint : object.Array("waypoints")) {
    const MotionWaypoint w = ReadWaypoint(waypoint.AsObject());
    if (!motion.waypoints.empty() && !(w.t > motion.waypoints.back().t)) {
      waypoint.Field("t").Fail("a time after the previous waypoint's " +
                               Shown(motion.waypoints.back().t));
    }
    motion.waypoints.push_back(w);
  }
  std::string why;
  if (!IsWellFormed(motion, &why)) object.Fail("a well-formed grasping motion (" + why + ")");
  return motion;
}

// A version-2 "placement" of a score or entry with orientation theta_deg: its position, and
// its theta_deg checked against the one given.
Eigen::Vector2d ReadPlacement(const JsonReader& object, double theta_deg) {
  const JsonReader p = object.Field("placement").AsObject();
  const Eigen::Vector2d xy(p.NumberIn("x", -5.0, 5.0), p.NumberIn("y", -5.0, 5.0));
  if (p.Number("theta_deg") != theta_deg) {
    p.Field("theta_deg").Fail("the theta_deg " + Shown(theta_deg) + " beside it");
  }
  return xy;
}

DemoScore ReadScore(const JsonReader& object, bool v2) {
  object.AsObject();
  DemoScore s;
  s.file = object.String("file");
  s.trial = object.String("trial");
  s.theta_deg = object.Number("theta_deg");
  if (v2) s.xy = ReadPlacement(object, s.theta_deg);
  s.trials = static_cast<int>(object.Integer("trials", 0, std::numeric_limits<int>::max()));
  s.successes = static_cast<int>(object.Integer("successes", 0, s.trials));
  s.score = Probability(object, "score");
  s.ci_low = Probability(object, "ci_low");
  s.ci_high = Probability(object, "ci_high");
  if (s.ci_low > s.ci_high) {
    object.Field("ci_low").Fail("a bound at most ci_high " + Shown(s.ci_high));
  }
  s.nominal_success = object.Bool("nominal_success");
  s.seed = object.Unsigned("seed");
  s.failures = object.String("failures");
  s.selected = object.Bool("selected");
  if (object.Has("stopped")) s.stopped = object.String("stopped");
  return s;
}

LibraryEntry ReadEntry(const JsonReader& object, bool v2) {
  object.AsObject();
  LibraryEntry e;
  e.theta_deg = object.Number("theta_deg");
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  if (v2) xy = ReadPlacement(object, e.theta_deg);
  e.file = object.String("file");
  e.trial = object.String("trial");
  e.score = Probability(object, "score");
  e.lift_height = object.Number("lift_height");
  e.lift_duration = object.NumberIn("lift_duration", 0.0, INFINITY);
  e.motion = ReadMotion(object.Field("motion"), e.theta_deg);
  if (v2 && (e.motion.p_WO.head<2>() - xy).norm() > kSamePosition) {
    object.Field("placement")
        .Fail("the motion's object_position in x and y (" + Shown(e.motion.p_WO.x()) + ", " +
              Shown(e.motion.p_WO.y()) + ")");
  }
  return e;
}

GraspLibrary ReadLibrary(const JsonReader& document) {
  const JsonReader format = document.AsObject().Field("format");
  const bool v2 = format.IsString() && format.AsString() == kLibraryFormatV2;
  if (!v2) document.ExpectString("format", kLibraryFormat);
  GraspLibrary library;
  library.demo_directory = document.String("demo_directory");
  library.seed = document.Unsigned("seed");
  library.perturbations =
      static_cast<int>(document.Integer("perturbations", 0, std::numeric_limits<int>::max()));
  library.tie_rule = document.String("tie_rule");
  for (const JsonReader& score : document.Array("scores")) {
    library.scores.push_back(ReadScore(score, v2));
  }
  for (const JsonReader& entry : document.Array("entries")) {
    // the order is checked before the entry's motion, which must match its theta.
    const double theta_deg = entry.AsObject().Number("theta_deg");
    if (v2) {
      const Eigen::Vector2d xy = ReadPlacement(entry, theta_deg);
      if (!library.entries.empty()) {
        const LibraryEntry& b = library.entries.back();
        if (!PlacementBefore(b.motion.p_WO.head<2>(), b.theta_deg, xy, theta_deg)) {
          entry.Field("placement")
              .Fail("a placement after the previous entry's (x, then y, then theta: " +
                    Shown(b.motion.p_WO.x()) + ", " + Shown(b.motion.p_WO.y()) + ", " +
                    Shown(b.theta_deg) + ")");
        }
      }
    } else if (!library.entries.empty() && !(theta_deg > library.entries.back().theta_deg)) {
      entry.Field("theta_deg")
          .Fail("a theta above the previous entry's " + Shown(library.entries.back().theta_deg));
    }
    library.entries.push_back(ReadEntry(entry, v2));
  }
  return library;
}

}  // namespace

bool PlacementBefore(const Eigen::Vector2d& xy_a, double theta_a, const Eigen::Vector2d& xy_b,
                     double theta_b) {
  if (std::abs(xy_a.x() - xy_b.x()) > kSamePosition) return xy_a.x() < xy_b.x();
  if (std::abs(xy_a.y() - xy_b.y()) > kSamePosition) return xy_a.y() < xy_b.y();
  return theta_a < theta_b;
}

bool GraspLibrary::HasPositions() const {
  for (const LibraryEntry& e : entries) {
    if ((e.motion.p_WO.head<2>() - entries.front().motion.p_WO.head<2>()).norm() > kSamePosition) {
      return true;
    }
  }
  for (const DemoScore& s : scores) {
    if ((s.xy - scores.front().xy).norm() > kSamePosition) return true;
  }
  return false;
}

SelectionReplays CountSelectionReplays(const GraspLibrary& library) {
  SelectionReplays r;
  for (const DemoScore& s : library.scores) {
    r.ran += s.trials;
    r.all += library.perturbations;
    r.stopped += !s.stopped.empty();
  }
  return r;
}

std::string GraspLibraryToJson(const GraspLibrary& library) {
  return LibraryJson(library).dump(2) + "\n";
}

void WriteGraspLibrary(const GraspLibrary& library, const std::filesystem::path& path) {
  const std::string text = GraspLibraryToJson(library);
  // what the reader would reject is never written: the same checks on the document.
  ReadLibrary(JsonReader::Parse(text, path.string() + " (being written)"));
  WriteFileAtomically(path, text);
}

GraspLibrary ParseGraspLibrary(std::string_view json_text, const std::string& source) {
  GraspLibrary library = ReadLibrary(JsonReader::Parse(json_text, source));
  library.source = source;
  return library;
}

GraspLibrary ReadGraspLibrary(const std::filesystem::path& path) {
  GraspLibrary library = ReadLibrary(JsonReader::Load(path, input_kind::kLibrary));
  library.source = path.string();
  return library;
}

std::filesystem::path DefaultGraspLibraryPath(const std::string& object_name) {
  return ObjectLearningDataDirectory(object_name) / "library.json";
}

}  // namespace graspsynth
