#pragma once

/// @file
/// A trial as simulated, for watching it again (`graspsynth simulate --trial-record`,
/// `graspsynth view --trial`): the robot's joints, the object's pose and the object-hand
/// contacts from the physics at a fixed interval of simulated time, and the trial's outcome.
/// Its file format `graspsynth-trial-record/1` (docs/formats.md):
///
///     {"format": "graspsynth-trial-record/1",
///      "trajectory": "examples/grasp_60deg.json",  the trajectory or grasp file simulated
///      "theta_deg": 60.0, "object_xy": [x, y],      the placement (object_xy optional)
///      "record_interval_s": 0.01,                   simulated time between frames
///      "outcome": "success", "reason": "...",       the trial's judgement (TrialOutcome)
///      "lift_m": 0.12, "max_lift_m": 0.12, "simulated_s": 7.9,
///      "frames": [{"t": 0.0, "arm": [7 rad], "hand": [16 rad],
///                  "object_position": [x, y, z], "object_quaternion": [w, x, y, z],
///                  "contacts": [{"p": [x, y, z], "f": N, "link": j}, ...]}, ...]}
///
/// World frame, metres, radians, seconds, newtons; numbers rounded to 1e-6; one frame per line.
/// The fields are listed once (VisitFields below): the writer (FieldsJson) and the reader
/// (ReadFieldsJson) are made from the lists.

#include <Eigen/Geometry>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/field_list.hpp"
#include "common/json_reader.hpp"
#include "kinematics/types.hpp"
#include "motion/joint_trajectory.hpp"
#include "simulation/trial.hpp"
#include "simulation/trial_judge.hpp"

namespace graspsynth {

/// The `format` value of a trial record.
inline constexpr std::string_view kTrialRecordFormat = "graspsynth-trial-record/1";

/// One object-hand contact of a frame.
struct RecordedContact {
  Eigen::Vector3d p_WC = Eigen::Vector3d::Zero();  ///< contact point, world, m
  double force = 0.0;  ///< magnitude of the force it put on the object, N (0: detection only)
  int hand_link = -1;  ///< HandJointVector index of the finger link, 20 for the palm or mount
};

/// The simulated state at one instant.
struct TrialRecordFrame {
  double t = 0.0;                                            ///< simulated time, s
  Vector7d arm = Vector7d::Zero();                           ///< measured arm joints, rad
  HandVector hand = HandVector::Zero();                      ///< measured f0..f15, rad
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();            ///< object centre, world, m
  Eigen::Quaterniond q_WO = Eigen::Quaterniond::Identity();  ///< object orientation, world
  std::vector<RecordedContact> contacts;                     ///< object-hand contacts
};

/// A whole trial as simulated.
struct TrialRecord {
  std::string format = std::string(kTrialRecordFormat);
  std::string trajectory;                    ///< the simulated file, as the user named it
  double theta_deg = 0.0;                    ///< object orientation, deg
  std::optional<Eigen::Vector2d> object_xy;  ///< object centre on the table, world, m
  double record_interval = 0.0;              ///< s of simulated time between frames
  TrialOutcome outcome = TrialOutcome::kUnstable;
  std::string reason;                    ///< the judgement's sentence
  double lift = 0.0;                     ///< object centre above its rest height at the end, m
  double max_lift = 0.0;                 ///< highest it got, m
  double simulated_time = 0.0;           ///< s
  std::vector<TrialRecordFrame> frames;  ///< at least one, strictly increasing t

  bool success() const { return outcome == TrialOutcome::kSuccess; }
};

/// RecordedContact's fields.
template <class V, class Row>
requires SameStruct<Row, RecordedContact>
void VisitFields(V& v, Row& r) {
  v(Field("p_WC").Json("/p"), r.p_WC);
  v(Field("force").Json("/f"), r.force);
  v(Field("hand_link").Json("/link"), r.hand_link);
}

/// TrialRecordFrame's fields.
template <class V, class Row>
requires SameStruct<Row, TrialRecordFrame>
void VisitFields(V& v, Row& r) {
  v(Field("t").Json("/t"), r.t);
  v(Field("arm").Json("/arm"), r.arm);
  v(Field("hand").Json("/hand"), r.hand);
  v(Field("p_WO").Json("/object_position"), r.p_WO);
  v(Field("q_WO").Json("/object_quaternion"), r.q_WO);
  v(Field("contacts").Json("/contacts"), r.contacts);
}

/// TrialRecord's fields.
template <class V, class Row>
requires SameStruct<Row, TrialRecord>
void VisitFields(V& v, Row& r) {
  v(Field("format").Json("/format"), r.format);
  v(Field("trajectory").Json("/trajectory"), r.trajectory);
  v(Field("theta_deg").Json("/theta_deg"), r.theta_deg);
  v(Field("object_xy").Json("/object_xy").OmitEmpty(), r.object_xy);
  v(Field("record_interval").Json("/record_interval_s"), r.record_interval);
  v(Field("outcome").Json("/outcome"), r.outcome);
  v(Field("reason").Json("/reason"), r.reason);
  v(Field("lift").Json("/lift_m"), r.lift);
  v(Field("max_lift").Json("/max_lift_m"), r.max_lift);
  v(Field("simulated_time").Json("/simulated_s"), r.simulated_time);
  v(Field("frames").Json("/frames"), r.frames);
}

/// A trial and its record.
struct RecordedTrial {
  TrialResult result;
  TrialRecord record;
};

/// Runs RunTrial(model, trajectory, options) with its states recorded (options.record_interval,
/// which must be > 0) and the object-hand contacts of every step observed, and makes its record:
/// the states as frames, each with the contacts of its step (points, force magnitudes), the
/// outcome and figures. `source` names the simulated file. The trial is the one RunTrial runs
/// with these options: observing changes nothing in it.
RecordedTrial RunRecordedTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                               const TrialOptions& options, const std::string& source);

/// The record as a `graspsynth-trial-record/1` document (see the file comment).
std::string TrialRecordToJson(const TrialRecord& record);

/// Reads a trial record document. Throws InputError (JsonReader's wording: the source, the
/// field path such as `frames[3].arm`, expected and found value) when `format` is not
/// kTrialRecordFormat, a field is missing (object_xy may be), unknown, of the wrong kind or not
/// finite, an outcome is not one of TrialOutcome's names, a quaternion is not unit, `frames` is
/// empty or its times do not strictly increase, or record_interval_s is not > 0.
TrialRecord ReadTrialRecord(const JsonReader& document);

/// Reads and parses a trial record file (ReadTrialRecord). Throws InputError naming the file.
TrialRecord LoadTrialRecord(const std::filesystem::path& path);

/// Writes TrialRecordToJson atomically (temporary file + rename). Throws InputError.
void WriteTrialRecord(const std::filesystem::path& path, const TrialRecord& record);

}  // namespace graspsynth
