#include "teleop/calibration.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common/data_dir.hpp"
#include "common/errors.hpp"

namespace graspsynth::teleop {
namespace {

using nlohmann::json;

[[noreturn]] void Fail(const std::string& source, const std::string& what) {
  throw InputError(source + ": " + what);
}

std::vector<double> Numbers(const json& value, size_t count, const std::string& source,
                            const std::string& field) {
  if (!value.is_array() || value.size() != count) {
    Fail(source,
         field + " must be an array of " + std::to_string(count) + " numbers, not " + value.dump());
  }
  std::vector<double> numbers;
  for (const json& v : value) {
    if (!v.is_number() || !std::isfinite(v.get<double>())) {
      Fail(source, field + " holds " + v.dump() + ", not a finite number");
    }
    numbers.push_back(v.get<double>());
  }
  return numbers;
}

Eigen::Isometry3d Pose(const json& value, const std::string& source, const std::string& field) {
  if (!value.is_object()) Fail(source, field + " must be an object, not " + value.dump());
  for (const auto& [key, unused] : value.items()) {
    if (key != "position" && key != "quaternion") {
      Fail(source, field + " has the unknown key \"" + key + "\"");
    }
  }
  if (!value.contains("position")) Fail(source, field + ".position is missing");
  if (!value.contains("quaternion")) Fail(source, field + ".quaternion is missing");
  const std::vector<double> p = Numbers(value["position"], 3, source, field + ".position");
  const std::vector<double> q = Numbers(value["quaternion"], 4, source, field + ".quaternion");
  Eigen::Quaterniond quaternion(q[0], q[1], q[2], q[3]);
  if (std::abs(quaternion.norm() - 1.0) > 1e-6) {
    Fail(source, field + ".quaternion " + value["quaternion"].dump() + " is not unit (norm " +
                     std::to_string(quaternion.norm()) + ")");
  }
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = quaternion.normalized().toRotationMatrix();
  X.translation() = Eigen::Vector3d(p[0], p[1], p[2]);
  return X;
}

}  // namespace

TeleopCalibration ParseTeleopCalibration(std::string_view json_text, const std::string& source) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::exception& e) {
    Fail(source, std::string("not valid JSON: ") + e.what());
  }
  if (!doc.is_object()) Fail(source, "the document must be a JSON object");
  for (const auto& [key, unused] : doc.items()) {
    if (key != "format" && key != "tracker_in_world" && key != "sensor_to_wrist") {
      Fail(source, "unknown key \"" + key + "\"");
    }
  }
  if (!doc.contains("format") || !doc["format"].is_string() ||
      doc["format"].get<std::string>() != kTeleopConfigFormat) {
    Fail(source, "format must be \"" + std::string(kTeleopConfigFormat) + "\", not " +
                     (doc.contains("format") ? doc["format"].dump() : std::string("missing")));
  }
  if (!doc.contains("tracker_in_world")) Fail(source, "tracker_in_world is missing");
  TeleopCalibration calibration;
  calibration.X_WT = Pose(doc["tracker_in_world"], source, "tracker_in_world");
  if (doc.contains("sensor_to_wrist")) {
    calibration.X_SH = Pose(doc["sensor_to_wrist"], source, "sensor_to_wrist");
  }
  return calibration;
}

TeleopCalibration LoadTeleopCalibration(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return ParseTeleopCalibration(text.str(), path.string());
}

std::filesystem::path DefaultTeleopCalibrationPath() {
  return DataDirectory() / "examples" / "teleop_calibration.json";
}

}  // namespace graspsynth::teleop
