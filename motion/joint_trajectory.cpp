#include "motion/joint_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

// Marks bare non-finite tokens (NaN, Infinity, as Python's json module writes them) that JSON
// does not allow, so that the field check below can name the sample and field holding them
// instead of the parser reporting a byte offset.
constexpr std::string_view kNonFiniteMark = "\x01non-finite:";

std::string MarkNonFiniteTokens(std::string_view text) {
  static constexpr std::string_view kTokens[] = {"-Infinity", "Infinity", "-NaN", "NaN",
                                                 "-nan",      "nan",      "-inf", "inf"};
  std::string out;
  out.reserve(text.size());
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      out += c;
      if (c == '\\' && i + 1 < text.size()) {
        out += text[++i];
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
      out += c;
      continue;
    }
    bool replaced = false;
    for (std::string_view token : kTokens) {
      if (text.substr(i, token.size()) == token) {
        out += "\"\\u0001non-finite:";  // parses to kNonFiniteMark
        out += token;
        out += '"';
        i += token.size() - 1;
        replaced = true;
        break;
      }
    }
    if (!replaced) out += c;
  }
  return out;
}

std::string Show(const json& v) {
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s.rfind(kNonFiniteMark, 0) == 0) return s.substr(kNonFiniteMark.size());
  }
  return v.dump();
}

double FiniteNumber(const json& v, const std::string& where) {
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw InputError(where + " = " + Show(v) + " is not a finite number");
  }
  return v.get<double>();
}

const json& Field(const json& object, const std::string& key, const std::string& where) {
  if (!object.is_object()) throw InputError(where + " is not a JSON object");
  const auto it = object.find(key);
  if (it == object.end()) throw InputError(where + "." + key + " is missing");
  return *it;
}

template <int N>
Eigen::Matrix<double, N, 1> FiniteVector(const json& v, const std::string& where) {
  if (!v.is_array()) throw InputError(where + " = " + Show(v) + " is not an array");
  if (v.size() != static_cast<size_t>(N)) {
    throw InputError(where + " has " + std::to_string(v.size()) + " values, expected " +
                     std::to_string(N));
  }
  Eigen::Matrix<double, N, 1> out;
  for (int i = 0; i < N; ++i) out[i] = FiniteNumber(v[i], where + "[" + std::to_string(i) + "]");
  return out;
}

std::string Number(double x) {
  std::ostringstream s;
  s.precision(10);
  s << x;
  return s.str();
}

double Rounded(double x) {
  const double r = std::round(x * 1e10) / 1e10;
  return r == 0.0 ? 0.0 : r;  // no "-0.0" in files
}

json RoundedArray(const double* data, int n) {
  json a = json::array();
  for (int i = 0; i < n; ++i) a.push_back(Rounded(data[i]));
  return a;
}

}  // namespace

Eigen::Isometry3d WristWaypoint::pose() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = q_WH.normalized().toRotationMatrix();
  X.translation() = p_WH;
  return X;
}

TrajectorySample SampleAt(const JointTrajectory& trajectory, double t) {
  const std::vector<TrajectorySample>& s = trajectory.samples;
  if (t <= s.front().t) return s.front();
  if (t >= s.back().t) return s.back();
  const auto next = std::upper_bound(
      s.begin(), s.end(), t, [](double time, const TrajectorySample& x) { return time < x.t; });
  const TrajectorySample& b = *next;
  const TrajectorySample& a = *(next - 1);
  const double u = (t - a.t) / (b.t - a.t);
  TrajectorySample out;
  out.t = t;
  out.arm = (1.0 - u) * a.arm + u * b.arm;
  out.hand = (1.0 - u) * a.hand + u * b.hand;
  return out;
}

JointTrajectory TimeScaled(const JointTrajectory& trajectory, double factor) {
  JointTrajectory out = trajectory;
  for (TrajectorySample& s : out.samples) s.t *= factor;
  for (WristWaypoint& w : out.waypoints) w.t *= factor;
  return out;
}

JointTrajectory ParseJointTrajectory(std::string_view json_text, const std::string& source) {
  json root;
  try {
    root = json::parse(MarkNonFiniteTokens(json_text));
  } catch (const json::parse_error& e) {
    throw InputError(source + ": not valid JSON: " + e.what());
  }
  if (!root.is_object()) throw InputError(source + ": the document is not a JSON object");
  const json& format = Field(root, "format", source);
  if (!format.is_string() || format.get<std::string>() != kJointTrajectoryFormat) {
    throw InputError(source + ": format = " + Show(format) + " is not \"" +
                     std::string(kJointTrajectoryFormat) + "\"");
  }
  JointTrajectory trajectory;
  trajectory.theta_deg = FiniteNumber(Field(root, "theta_deg", source), source + ": theta_deg");

  const json& samples = Field(root, "samples", source);
  if (!samples.is_array() || samples.empty()) {
    throw InputError(source + ": samples must be a non-empty array");
  }
  for (size_t i = 0; i < samples.size(); ++i) {
    const std::string where = source + ": samples[" + std::to_string(i) + "]";
    TrajectorySample s;
    s.t = FiniteNumber(Field(samples[i], "t", where), where + ".t");
    s.arm = FiniteVector<kArmDof>(Field(samples[i], "arm", where), where + ".arm");
    s.hand = FiniteVector<kHandDof>(Field(samples[i], "hand", where), where + ".hand");
    if (i > 0 && !(s.t > trajectory.samples.back().t)) {
      throw InputError(where + ".t = " + Number(s.t) + " does not increase (previous sample " +
                       Number(trajectory.samples.back().t) + ")");
    }
    trajectory.samples.push_back(s);
  }

  if (const auto it = root.find("waypoints"); it != root.end()) {
    if (!it->is_array()) throw InputError(source + ": waypoints must be an array");
    for (size_t i = 0; i < it->size(); ++i) {
      const json& w = (*it)[i];
      const std::string where = source + ": waypoints[" + std::to_string(i) + "]";
      WristWaypoint p;
      p.t = FiniteNumber(Field(w, "t", where), where + ".t");
      p.p_WH = FiniteVector<3>(Field(w, "position", where), where + ".position");
      const Eigen::Vector4d q =
          FiniteVector<4>(Field(w, "quaternion", where), where + ".quaternion");
      if (std::abs(q.norm() - 1.0) > 1e-6) {
        throw InputError(where + ".quaternion has norm " + Number(q.norm()) + ", not 1");
      }
      p.q_WH = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized();
      if (!trajectory.waypoints.empty() && !(p.t > trajectory.waypoints.back().t)) {
        throw InputError(where + ".t = " + Number(p.t) + " does not increase (previous waypoint " +
                         Number(trajectory.waypoints.back().t) + ")");
      }
      trajectory.waypoints.push_back(p);
    }
  }
  return trajectory;
}

void CheckJointLimits(const JointTrajectory& trajectory, const ArmModel& arm, const HandModel& hand,
                      const std::string& source, double tol) {
  for (size_t i = 0; i < trajectory.samples.size(); ++i) {
    const TrajectorySample& s = trajectory.samples[i];
    const std::string where = source + ": samples[" + std::to_string(i) + "]";
    for (int j = 0; j < kArmDof; ++j) {
      if (s.arm[j] < arm.lower()[j] - tol || s.arm[j] > arm.upper()[j] + tol) {
        throw InputError(where + ".arm[" + std::to_string(j) + "] = " + Number(s.arm[j]) + " (" +
                         arm.joint(j).name + ") is outside its limits [" + Number(arm.lower()[j]) +
                         ", " + Number(arm.upper()[j]) + "] rad");
      }
    }
    for (int k = 0; k < kHandDof; ++k) {
      if (s.hand[k] < hand.lower()[k] - tol || s.hand[k] > hand.upper()[k] + tol) {
        throw InputError(where + ".hand[" + std::to_string(k) + "] = " + Number(s.hand[k]) + " (" +
                         hand.actuated_names()[k] + ") is outside its limits [" +
                         Number(hand.lower()[k]) + ", " + Number(hand.upper()[k]) + "] rad");
      }
    }
  }
}

JointTrajectory LoadJointTrajectory(const std::filesystem::path& path, const ArmModel& arm,
                                    const HandModel& hand) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot open trajectory file '" + path.string() + "'");
  std::stringstream text;
  text << in.rdbuf();
  JointTrajectory trajectory = ParseJointTrajectory(text.str(), path.string());
  CheckJointLimits(trajectory, arm, hand, path.string());
  return trajectory;
}

std::string JointTrajectoryToJson(const JointTrajectory& trajectory) {
  std::string out = "{\n  \"format\": \"" + std::string(kJointTrajectoryFormat) + "\",\n";
  out += "  \"theta_deg\": " + json(Rounded(trajectory.theta_deg)).dump() + ",\n";
  out += "  \"samples\": [\n";
  for (size_t i = 0; i < trajectory.samples.size(); ++i) {
    const TrajectorySample& s = trajectory.samples[i];
    const nlohmann::ordered_json line = {{"t", Rounded(s.t)},
                                         {"arm", RoundedArray(s.arm.data(), kArmDof)},
                                         {"hand", RoundedArray(s.hand.data(), kHandDof)}};
    out += "    " + line.dump() + (i + 1 < trajectory.samples.size() ? ",\n" : "\n");
  }
  out += "  ]";
  if (!trajectory.waypoints.empty()) {
    out += ",\n  \"waypoints\": [\n";
    for (size_t i = 0; i < trajectory.waypoints.size(); ++i) {
      const WristWaypoint& w = trajectory.waypoints[i];
      Eigen::Quaterniond q = w.q_WH.normalized();
      if (q.w() < 0.0) q.coeffs() = -q.coeffs();
      const double qv[4] = {q.w(), q.x(), q.y(), q.z()};
      const nlohmann::ordered_json line = {{"t", Rounded(w.t)},
                                           {"position", RoundedArray(w.p_WH.data(), 3)},
                                           {"quaternion", RoundedArray(qv, 4)}};
      out += "    " + line.dump() + (i + 1 < trajectory.waypoints.size() ? ",\n" : "\n");
    }
    out += "  ]";
  }
  out += "\n}\n";
  return out;
}

void WriteJointTrajectory(const std::filesystem::path& path, const JointTrajectory& trajectory) {
  WriteFileAtomically(path, JointTrajectoryToJson(trajectory));
}

}  // namespace graspsynth
