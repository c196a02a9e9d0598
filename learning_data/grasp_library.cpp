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
#include "common/json_reader.hpp"
#include "kinematics/pose_math.hpp"
#include "learning_data/demo_directory.hpp"

namespace graspsynth {
namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kLibraryFormat = "graspsynth-library/1";
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

json LibraryJson(const GraspLibrary& library) {
  json scores = json::array();
  for (const DemoScore& s : library.scores) {
    scores.push_back({{"file", s.file},
                      {"trial", s.trial},
                      {"theta_deg", s.theta_deg},
                      {"trials", s.trials},
                      {"successes", s.successes},
                      {"score", s.score},
                      {"ci_low", s.ci_low},
                      {"ci_high", s.ci_high},
                      {"nominal_success", s.nominal_success},
                      {"seed", s.seed},
                      {"failures", s.failures},
                      {"selected", s.selected}});
    if (!s.stopped.empty()) scores.back()["stopped"] = s.stopped;
  }
  json entries = json::array();
  for (const LibraryEntry& e : library.entries) {
    entries.push_back({{"theta_deg", e.theta_deg},
                       {"file", e.file},
                       {"trial", e.trial},
                       {"score", e.score},
                       {"lift_height", e.lift_height},
                       {"lift_duration", e.lift_duration},
                       {"motion", MotionJson(e.motion)}});
  }
  json j;
  j["format"] = kLibraryFormat;
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

DemoScore ReadScore(const JsonReader& object) {
  object.AsObject();
  DemoScore s;
  s.file = object.String("file");
  s.trial = object.String("trial");
  s.theta_deg = object.Number("theta_deg");
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

LibraryEntry ReadEntry(const JsonReader& object) {
  object.AsObject();
  LibraryEntry e;
  e.theta_deg = object.Number("theta_deg");
  e.file = object.String("file");
  e.trial = object.String("trial");
  e.score = Probability(object, "score");
  e.lift_height = object.Number("lift_height");
  e.lift_duration = object.NumberIn("lift_duration", 0.0, INFINITY);
  e.motion = ReadMotion(object.Field("motion"), e.theta_deg);
  return e;
}

GraspLibrary ReadLibrary(const JsonReader& document) {
  document.AsObject().ExpectString("format", kLibraryFormat);
  GraspLibrary library;
  library.demo_directory = document.String("demo_directory");
  library.seed = document.Unsigned("seed");
  library.perturbations =
      static_cast<int>(document.Integer("perturbations", 0, std::numeric_limits<int>::max()));
  library.tie_rule = document.String("tie_rule");
  for (const JsonReader& score : document.Array("scores")) {
    library.scores.push_back(ReadScore(score));
  }
  for (const JsonReader& entry : document.Array("entries")) {
    // the order is checked before the entry's motion, which must match its theta.
    const double theta_deg = entry.AsObject().Number("theta_deg");
    if (!library.entries.empty() && !(theta_deg > library.entries.back().theta_deg)) {
      entry.Field("theta_deg")
          .Fail("a theta above the previous entry's " + Shown(library.entries.back().theta_deg));
    }
    library.entries.push_back(ReadEntry(entry));
  }
  return library;
}

}  // namespace

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
  GraspLibrary library = ReadLibrary(JsonReader::Load(path));
  library.source = path.string();
  return library;
}

std::filesystem::path DefaultGraspLibraryPath(const std::string& object_name) {
  return ObjectLearningDataDirectory(object_name) / "library.json";
}

}  // namespace graspsynth
