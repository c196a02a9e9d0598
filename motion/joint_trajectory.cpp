#include "motion/joint_trajectory.hpp"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/input_file.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;

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
  Eigen::Isometry3d X = PoseFrom(p_WH, q_WH.normalized());
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

namespace {

TrajectorySample ReadSample(const JsonReader& object) {
  TrajectorySample s;
  s.t = object.Number("t");
  s.arm = object.Numbers("arm", kArmDof);
  s.hand = object.Numbers("hand", kHandDof);
  return s;
}

WristWaypoint ReadWaypoint(const JsonReader& object) {
  WristWaypoint p;
  p.t = object.Number("t");
  p.p_WH = object.Vector3("position");
  p.q_WH = object.UnitQuaternion("quaternion", 1e-6).normalized();
  return p;
}

}  // namespace

JointTrajectory ReadJointTrajectory(const JsonReader& object) {
  object.AsObject().ExpectString("format", kJointTrajectoryFormat);
  JointTrajectory trajectory;
  trajectory.theta_deg = object.Number("theta_deg");
  if (object.Has("object_xy")) {
    trajectory.object_xy = Eigen::Vector2d(object.Numbers("object_xy", 2, -5.0, 5.0));
  }

  const JsonReader samples = object.Field("samples");
  const std::vector<JsonReader> sample_objects = samples.AsArray();
  if (sample_objects.empty()) samples.Fail("a non-empty array of samples");
  for (const JsonReader& sample : sample_objects) {
    const TrajectorySample s = ReadSample(sample.AsObject());
    if (!trajectory.samples.empty() && !(s.t > trajectory.samples.back().t)) {
      sample.Field("t").Fail("a time after the previous sample's " +
                             StreamNumber(trajectory.samples.back().t, 10));
    }
    trajectory.samples.push_back(s);
  }

  if (const auto waypoints = object.OptionalField("waypoints")) {
    for (const JsonReader& waypoint : waypoints->AsArray()) {
      const WristWaypoint p = ReadWaypoint(waypoint.AsObject());
      if (!trajectory.waypoints.empty() && !(p.t > trajectory.waypoints.back().t)) {
        waypoint.Field("t").Fail("a time after the previous waypoint's " +
                                 StreamNumber(trajectory.waypoints.back().t, 10));
      }
      trajectory.waypoints.push_back(p);
    }
  }
  return trajectory;
}

JointTrajectory ParseJointTrajectory(std::string_view json_text, const std::string& source) {
  return ReadJointTrajectory(JsonReader::Parse(json_text, source));
}

void CheckJointLimits(const JointTrajectory& trajectory, const ArmModel& arm, const HandModel& hand,
                      const std::string& source, double tol, const std::string& field_prefix) {
  auto fail = [&](size_t i, const char* part, int j, double v, const std::string& name, double lo,
                  double hi) {
    throw InputError(source + ": field '" + field_prefix + "samples[" + std::to_string(i) + "]." +
                     part + "[" + std::to_string(j) + "]': expected a value within " + name +
                     "'s limits [" + StreamNumber(lo, 10) + ", " + StreamNumber(hi, 10) +
                     "] rad, found " + StreamNumber(v, 10));
  };
  for (size_t i = 0; i < trajectory.samples.size(); ++i) {
    const TrajectorySample& s = trajectory.samples[i];
    for (int j = 0; j < kArmDof; ++j) {
      if (s.arm[j] < arm.lower()[j] - tol || s.arm[j] > arm.upper()[j] + tol) {
        fail(i, "arm", j, s.arm[j], arm.joint(j).name, arm.lower()[j], arm.upper()[j]);
      }
    }
    for (int k = 0; k < kHandDof; ++k) {
      if (s.hand[k] < hand.lower()[k] - tol || s.hand[k] > hand.upper()[k] + tol) {
        fail(i, "hand", k, s.hand[k], hand.actuated_names()[k], hand.lower()[k], hand.upper()[k]);
      }
    }
  }
}

JointTrajectory LoadJointTrajectory(const std::filesystem::path& path, const ArmModel& arm,
                                    const HandModel& hand) {
  JointTrajectory trajectory =
      ParseJointTrajectory(ReadInputFile(path, input_kind::kTrajectory), path.string());
  CheckJointLimits(trajectory, arm, hand, path.string());
  return trajectory;
}

std::string JointTrajectoryToJson(const JointTrajectory& trajectory) {
  std::string out = "{\n  \"format\": \"" + std::string(kJointTrajectoryFormat) + "\",\n";
  out += "  \"theta_deg\": " + json(Rounded(trajectory.theta_deg)).dump() + ",\n";
  if (trajectory.object_xy) {
    out += "  \"object_xy\": " + json(RoundedArray(trajectory.object_xy->data(), 2)).dump() + ",\n";
  }
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
      const Eigen::Quaterniond q = Canonical(w.q_WH);
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
