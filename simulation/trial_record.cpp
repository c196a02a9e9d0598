#include "simulation/trial_record.hpp"

#include <cmath>
#include <concepts>
#include <nlohmann/json.hpp>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/demand.hpp"
#include "common/field_json_reader.hpp"
#include "common/field_text.hpp"
#include "kinematics/pose_math.hpp"
#include "simulation/simulation_fields.hpp"

namespace graspsynth {
namespace {

using json = nlohmann::ordered_json;

// 1e-6: a micrometre, a microradian; far below what a viewer shows, and short numbers.
double Round6(double x) {
  const double r = std::round(x * 1e6) / 1e6;
  return r == 0.0 ? 0.0 : r;  // no "-0.0"
}

// The record's numbers rounded (FieldsJson's forms of these types).
struct Rounded {
  template <class T>
  requires std::same_as<T, double> json operator()(const T& x) const { return Round6(x); }
  template <class T>
  requires field_detail::FixedEigenVector<T> json operator()(const T& v) const {
    json a = json::array();
    for (int i = 0; i < v.size(); ++i) a.push_back(Round6(v[i]));
    return a;
  }
  template <class T>
  requires std::same_as<T, Eigen::Quaterniond> json operator()(const T& q) const {
    const Eigen::Quaterniond c = Canonical(q);
    return json::array({Round6(c.w()), Round6(c.x()), Round6(c.y()), Round6(c.z())});
  }
};

}  // namespace

RecordedTrial RunRecordedTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                               const TrialOptions& options, const std::string& source) {
  GS_DEMAND(options.record_interval > 0.0, "a trial record needs a record interval");
  // the contacts of every step, by the step's time (a recorded state's time is its step's).
  std::vector<std::pair<double, std::vector<RecordedContact>>> steps;
  const StepObserver observer = [&steps](SimulationData& data) {
    std::vector<RecordedContact> contacts;
    for (const HandObjectContact& c : data.hand_object_contacts()) {
      contacts.push_back({c.p_WC, c.f_W.norm(), c.hand_link});
    }
    steps.emplace_back(data.time(), std::move(contacts));
  };
  RecordedTrial out;
  out.result = RunTrial(model, trajectory, options, observer);
  const TrialResult& result = out.result;
  TrialRecord& record = out.record;
  record.trajectory = source;
  record.theta_deg = trajectory.theta_deg;
  record.object_xy = trajectory.object_xy;
  record.record_interval = options.record_interval;
  record.outcome = result.outcome;
  record.reason = result.reason;
  record.lift = result.lift;
  record.max_lift = result.max_lift;
  record.simulated_time = result.simulated_time;
  size_t k = 0;  // the steps and the states are both in time order
  for (const TrialState& s : result.states) {
    TrialRecordFrame frame;
    frame.t = s.t;
    frame.arm = s.arm;
    frame.hand = s.hand;
    frame.p_WO = s.X_WO.translation();
    frame.q_WO = Eigen::Quaterniond(s.X_WO.linear());
    while (k < steps.size() && steps[k].first < s.t - 1e-9) ++k;
    if (k < steps.size() && std::abs(steps[k].first - s.t) <= 1e-9) {
      frame.contacts = steps[k].second;
    }
    record.frames.push_back(std::move(frame));
  }
  return out;
}

std::string TrialRecordToJson(const TrialRecord& record) {
  const json doc = FieldsJson<json>(record, Rounded{});
  // the head's keys one per line, then one frame per line.
  std::string text = "{\n";
  for (const auto& [key, value] : doc.items()) {
    if (key == "frames") continue;
    text.append(" ").append(json(key).dump()).append(": ").append(value.dump()).append(",\n");
  }
  text += " \"frames\": [";
  const json& frames = doc["frames"];
  for (size_t i = 0; i < frames.size(); ++i) {
    text.append(i == 0 ? "\n  " : ",\n  ").append(frames[i].dump());
  }
  return text + "\n ]\n}\n";
}

TrialRecord ReadTrialRecord(const JsonReader& document) {
  document.AsObject();
  document.ExpectString("format", kTrialRecordFormat);
  TrialRecord record;
  ReadFieldsJson(document, &record);
  if (!(record.record_interval > 0.0)) {
    document.Field("record_interval_s").Fail("a number > 0");
  }
  const std::vector<JsonReader> frames = document.Array("frames");
  if (frames.empty()) document.Field("frames").Fail("at least one frame");
  for (size_t i = 1; i < record.frames.size(); ++i) {
    if (!(record.frames[i].t > record.frames[i - 1].t)) {
      frames[i].Field("t").Fail("a time after the previous frame's " +
                                std::to_string(record.frames[i - 1].t) + " s");
    }
  }
  return record;
}

TrialRecord LoadTrialRecord(const std::filesystem::path& path) {
  return ReadTrialRecord(JsonReader::Load(path, input_kind::kJson));
}

void WriteTrialRecord(const std::filesystem::path& path, const TrialRecord& record) {
  WriteFileAtomically(path, TrialRecordToJson(record));
}

}  // namespace graspsynth
