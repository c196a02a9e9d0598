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

namespace graspsynth {
namespace {

using json = nlohmann::ordered_json;

constexpr std::string_view kLibraryFormat = "graspsynth-library/1";
constexpr double kDeg = M_PI / 180.0;
// a quaternion read from a library may be off unit by this much (rounding by other writers);
// it is then normalized, so that the motion passes IsWellFormed (1e-9).
constexpr double kQuaternionTolerance = 1e-6;
// theta_rad of a motion must agree with its entry's theta_deg this closely, rad.
constexpr double kThetaTolerance = 1e-9;

// Sign-normalized (w >= 0) and unit: divided by its norm unless that is already within 1e-15
// of 1, so that a unit quaternion is written (and read back) bit for bit.
Eigen::Quaterniond ForFile(const Eigen::Quaterniond& q) {
  Eigen::Quaterniond r = q;
  if (std::abs(r.norm() - 1.0) > 1e-15) r.normalize();
  if (r.w() < 0.0) r.coeffs() = -r.coeffs();
  return r;
}

json Vector(const Eigen::VectorXd& v) {
  json a = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(v[i]);
  return a;
}

json MotionJson(const GraspingMotion& motion) {
  json waypoints = json::array();
  for (const MotionWaypoint& w : motion.waypoints) {
    const Eigen::Quaterniond q = ForFile(w.q_WH);
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

// Strict reading of a parsed document: every accessor names the source and the field path
// (e.g. "entries[2].motion.waypoints[0].quaternion") and the offending value.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void Fail(const std::string& path, const std::string& what) const {
    throw InputError(source_ + ": " + path + ": " + what);
  }

  static std::string Shown(const json& v) {
    std::string text = v.dump();
    if (text.size() > 60) text = text.substr(0, 57) + "...";
    return text;
  }

  const json& Field(const json& object, const std::string& path, const char* key) const {
    if (!object.is_object()) Fail(path, "expected an object, got " + Shown(object));
    const auto it = object.find(key);
    if (it == object.end()) Fail(Join(path, key), "missing");
    return *it;
  }

  double Number(const json& object, const std::string& path, const char* key) const {
    return NumberValue(Field(object, path, key), Join(path, key));
  }

  double NumberValue(const json& v, const std::string& path) const {
    if (!v.is_number()) Fail(path, "expected a number, got " + Shown(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) Fail(path, "not a finite number: " + Shown(v));
    return x;
  }

  int Integer(const json& object, const std::string& path, const char* key, int lo) const {
    const json& v = Field(object, path, key);
    const std::string where = Join(path, key);
    if (!v.is_number_integer()) Fail(where, "expected an integer, got " + Shown(v));
    const int64_t x = v.get<int64_t>();
    if (x < lo || x > std::numeric_limits<int>::max()) {
      Fail(where, "out of range: " + Shown(v) + " (must be >= " + std::to_string(lo) + ")");
    }
    return static_cast<int>(x);
  }

  uint64_t Unsigned(const json& object, const std::string& path, const char* key) const {
    const json& v = Field(object, path, key);
    if (!v.is_number_unsigned()) {
      Fail(Join(path, key), "expected a non-negative integer, got " + Shown(v));
    }
    return v.get<uint64_t>();
  }

  bool Bool(const json& object, const std::string& path, const char* key) const {
    const json& v = Field(object, path, key);
    if (!v.is_boolean()) Fail(Join(path, key), "expected true or false, got " + Shown(v));
    return v.get<bool>();
  }

  std::string String(const json& object, const std::string& path, const char* key) const {
    const json& v = Field(object, path, key);
    if (!v.is_string()) Fail(Join(path, key), "expected a string, got " + Shown(v));
    return v.get<std::string>();
  }

  const json& Array(const json& object, const std::string& path, const char* key) const {
    const json& v = Field(object, path, key);
    if (!v.is_array()) Fail(Join(path, key), "expected an array, got " + Shown(v));
    return v;
  }

  Eigen::VectorXd Numbers(const json& object, const std::string& path, const char* key,
                          int count) const {
    const json& v = Array(object, path, key);
    const std::string where = Join(path, key);
    if (static_cast<int>(v.size()) != count) {
      Fail(where, "expected " + std::to_string(count) + " numbers, got " +
                      std::to_string(v.size()) + ": " + Shown(v));
    }
    Eigen::VectorXd x(count);
    for (int i = 0; i < count; ++i) {
      x[i] = NumberValue(v[i], where + "[" + std::to_string(i) + "]");
    }
    return x;
  }

  static std::string Join(const std::string& path, const char* key) {
    return path.empty() ? std::string(key) : path + "." + key;
  }
  static std::string Index(const std::string& path, size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }

 private:
  std::string source_;
};

double Probability(const Reader& r, const json& object, const std::string& path, const char* key) {
  const double x = r.Number(object, path, key);
  if (x < 0.0 || x > 1.0) {
    r.Fail(Reader::Join(path, key),
           "out of range: " + Reader::Shown(object.at(key)) + " (must be in [0, 1])");
  }
  return x;
}

GraspingMotion ReadMotion(const Reader& r, const json& j, const std::string& path,
                          double theta_deg) {
  GraspingMotion motion;
  motion.theta = r.Number(j, path, "theta_rad");
  if (std::abs(motion.theta - theta_deg * kDeg) > kThetaTolerance) {
    r.Fail(Reader::Join(path, "theta_rad"), "value " + Reader::Shown(j.at("theta_rad")) +
                                                " does not match the entry's theta_deg " +
                                                Reader::Shown(json(theta_deg)));
  }
  motion.p_WO = r.Numbers(j, path, "object_position", 3);
  motion.source = r.String(j, path, "source");
  const std::string wpath = Reader::Join(path, "waypoints");
  const json& waypoints = r.Array(j, path, "waypoints");
  for (size_t i = 0; i < waypoints.size(); ++i) {
    const std::string at = Reader::Index(wpath, i);
    const json& wj = waypoints[i];
    MotionWaypoint w;
    w.t = r.Number(wj, at, "t");
    if (i > 0 && !(w.t > motion.waypoints.back().t)) {
      r.Fail(Reader::Join(at, "t"), "time does not strictly increase: " + Reader::Shown(wj["t"]) +
                                        " after " + Reader::Shown(json(motion.waypoints.back().t)));
    }
    w.p_WH = r.Numbers(wj, at, "position", 3);
    const Eigen::Vector4d q = r.Numbers(wj, at, "quaternion", 4);
    w.q_WH = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
    const double norm = w.q_WH.norm();
    if (std::abs(norm - 1.0) > kQuaternionTolerance) {
      std::ostringstream why;
      why.precision(17);
      why << "not a unit quaternion (norm " << norm << "): " << Reader::Shown(wj["quaternion"]);
      r.Fail(Reader::Join(at, "quaternion"), why.str());
    }
    if (std::abs(norm - 1.0) > 1e-15) w.q_WH.normalize();
    w.f = r.Numbers(wj, at, "fingers", kHandDof);
    motion.waypoints.push_back(w);
  }
  std::string why;
  if (!IsWellFormed(motion, &why)) r.Fail(path, "not a well-formed grasping motion: " + why);
  return motion;
}

GraspLibrary ReadLibrary(const json& j, const std::string& source) {
  const Reader r(source);
  if (!j.is_object()) r.Fail("(document)", "expected a JSON object, got " + Reader::Shown(j));
  const std::string format = r.String(j, "", "format");
  if (format != kLibraryFormat) {
    r.Fail("format", "expected \"" + std::string(kLibraryFormat) + "\", got \"" + format + "\"");
  }
  GraspLibrary library;
  library.demo_directory = r.String(j, "", "demo_directory");
  library.seed = r.Unsigned(j, "", "seed");
  library.perturbations = r.Integer(j, "", "perturbations", 0);
  library.tie_rule = r.String(j, "", "tie_rule");

  const json& scores = r.Array(j, "", "scores");
  for (size_t i = 0; i < scores.size(); ++i) {
    const std::string at = Reader::Index("scores", i);
    const json& sj = scores[i];
    DemoScore s;
    s.file = r.String(sj, at, "file");
    s.trial = r.String(sj, at, "trial");
    s.theta_deg = r.Number(sj, at, "theta_deg");
    s.trials = r.Integer(sj, at, "trials", 0);
    s.successes = r.Integer(sj, at, "successes", 0);
    if (s.successes > s.trials) {
      r.Fail(Reader::Join(at, "successes"), "value " + std::to_string(s.successes) +
                                                " is more than trials (" +
                                                std::to_string(s.trials) + ")");
    }
    s.score = Probability(r, sj, at, "score");
    s.ci_low = Probability(r, sj, at, "ci_low");
    s.ci_high = Probability(r, sj, at, "ci_high");
    if (s.ci_low > s.ci_high) {
      r.Fail(Reader::Join(at, "ci_low"), "value " + Reader::Shown(sj["ci_low"]) +
                                             " is above ci_high " + Reader::Shown(sj["ci_high"]));
    }
    s.nominal_success = r.Bool(sj, at, "nominal_success");
    s.seed = r.Unsigned(sj, at, "seed");
    s.failures = r.String(sj, at, "failures");
    s.selected = r.Bool(sj, at, "selected");
    library.scores.push_back(s);
  }

  const json& entries = r.Array(j, "", "entries");
  for (size_t i = 0; i < entries.size(); ++i) {
    const std::string at = Reader::Index("entries", i);
    const json& ej = entries[i];
    LibraryEntry e;
    e.theta_deg = r.Number(ej, at, "theta_deg");
    if (i > 0 && !(e.theta_deg > library.entries.back().theta_deg)) {
      r.Fail(Reader::Join(at, "theta_deg"),
             "theta does not strictly increase: " + Reader::Shown(ej["theta_deg"]) + " after " +
                 Reader::Shown(json(library.entries.back().theta_deg)));
    }
    e.file = r.String(ej, at, "file");
    e.trial = r.String(ej, at, "trial");
    e.score = Probability(r, ej, at, "score");
    e.lift_height = r.Number(ej, at, "lift_height");
    e.lift_duration = r.Number(ej, at, "lift_duration");
    if (e.lift_duration < 0.0) {
      r.Fail(Reader::Join(at, "lift_duration"), "negative: " + Reader::Shown(ej["lift_duration"]));
    }
    e.motion = ReadMotion(r, r.Field(ej, at, "motion"), Reader::Join(at, "motion"), e.theta_deg);
    library.entries.push_back(std::move(e));
  }
  return library;
}

}  // namespace

void WriteGraspLibrary(const GraspLibrary& library, const std::filesystem::path& path) {
  const json j = LibraryJson(library);
  // what the reader would reject is never written: the same checks on the document.
  ReadLibrary(j, path.string() + " (being written)");
  WriteFileAtomically(path, j.dump(2) + "\n");
}

GraspLibrary ReadGraspLibrary(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot read the file (missing or unreadable)");
  std::stringstream text;
  text << in.rdbuf();
  json j;
  try {
    j = json::parse(text.str());
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    throw InputError(path.string() + ": not valid JSON: " + e.what());
  }
  return ReadLibrary(j, path.string());
}

std::filesystem::path DefaultGraspLibraryPath() {
  return DataDirectory() / "learning_data" / "library.json";
}

}  // namespace graspsynth
