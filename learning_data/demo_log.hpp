#pragma once

/// @file
/// The demonstration log, format v1 (DESIGN.md "Demonstration log format (v1)"): one CSV file per
/// teleoperation trial with `# key: value` metadata lines, a header row and one row per sample.
///
/// Validation rules of the reader (every violation is an InputError naming the file, the line and,
/// for a field, the column by 1-based index and name):
/// - the file is not empty and has a header and at least one sample row (a leading UTF-8
///   byte-order mark and CRLF line ends are accepted);
/// - lines before the header are `# key: value` metadata lines or blank; keys are unique;
///   `format: graspsynth-demo/1` (exactly), `theta_deg` (a finite number) and `object_position`
///   (three finite numbers x,y,z, comma-separated) are required; `sample_rate_hz` (if present) is
///   a finite number > 0; `trial` and `operator` are free text; other keys are kept as they are;
/// - the header is exactly the 28 columns of DemoColumns(), in that order;
/// - every sample row has 28 fields, each a finite decimal number (no nan, inf or empty field);
///   no blank or comment line between sample rows (blank lines at the end of the file are
///   allowed);
/// - `t` strictly increases; the wrist quaternion has norm 1 within kDemoQuaternionTolerance;
///   `event` is 0, 1 or 2; positions (the wrist, the object, `object_position`) lie within
///   kDemoMaxPosition of the origin, times within kDemoMaxTime, finger joints within
///   kDemoMaxJoint (bounds far beyond any robot's, that keep every sum and mean finite);
/// - exactly one grasp event (1) and exactly one end event (2), and the end event is on the last
///   row (a log without it is a truncated recording: the operator never pressed the final key).
///
/// Frames (kinematics/types.hpp): W world, H hand mount ("wrist"), O object centre.

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

/// The value of the required `format` metadata key.
inline constexpr std::string_view kDemoLogFormat = "graspsynth-demo/1";

/// Number of CSV columns of a sample row.
inline constexpr int kDemoColumnCount = 28;

/// The header row, column by column: t, wrist_x .. wrist_z, wrist_qw .. wrist_qz, f0 .. f15,
/// event, object_x .. object_z (kDemoColumnCount names).
const std::vector<std::string>& DemoColumns();

/// Tolerance on | |q| - 1 | of a wrist quaternion read from a log.
inline constexpr double kDemoQuaternionTolerance = 1e-3;
/// Largest |coordinate| of a position in a log, m.
inline constexpr double kDemoMaxPosition = 100.0;
/// Largest |t| in a log, s.
inline constexpr double kDemoMaxTime = 1e6;
/// Largest |f_i| of a finger joint in a log, rad.
inline constexpr double kDemoMaxJoint = 10.0;

/// The button event of a sample.
enum class DemoEvent : int {
  kNone = 0,   ///< no button pressed
  kGrasp = 1,  ///< the grasp button: this sample is the grasp pose
  kEnd = 2,    ///< the final key: end of the trial (always the last sample)
};

/// The metadata lines of a log.
struct DemoMetadata {
  std::string format{kDemoLogFormat};                         ///< always kDemoLogFormat
  double theta_deg = 0.0;                                     ///< object orientation, degrees
  Eigen::Vector3d object_position = Eigen::Vector3d::Zero();  ///< p_WO at rest, world, m
  std::optional<std::string> trial;                           ///< trial identifier, free text
  std::optional<std::string> operator_name;                   ///< key `operator`, free text
  std::optional<double> sample_rate_hz;                       ///< nominal sample rate, Hz
  /// Keys this version does not know, with their values, in file order (kept, never checked).
  std::vector<std::pair<std::string, std::string>> extra;
};

/// One row of a log.
struct DemoSample {
  double t = 0.0;                                            ///< s, strictly increasing
  Eigen::Vector3d p_WH = Eigen::Vector3d::Zero();            ///< wrist position, world, m
  Eigen::Quaterniond q_WH = Eigen::Quaterniond::Identity();  ///< wrist orientation (w,x,y,z)
  HandVector f = HandVector::Zero();                         ///< finger joints f0..f15, rad
  DemoEvent event = DemoEvent::kNone;                        ///< button event at this sample
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();            ///< object centre, world, m
};

/// A demonstration log: one teleoperation trial.
struct DemoLog {
  std::string source;  ///< where it was read from (file path), for messages and provenance
  DemoMetadata metadata;
  std::vector<DemoSample> samples;
};

/// Index of the first sample with `event`, or std::nullopt when there is none.
std::optional<size_t> FindEvent(const DemoLog& log, DemoEvent event);

/// Parses the text of a log. `source` names it in messages (usually the file path).
/// Throws InputError naming the source, the line and the column for any violation of the rules
/// in this file's description. Values are kept exactly as written (quaternions are not
/// normalized).
DemoLog ParseDemoLog(std::string_view text, const std::string& source);

/// Reads and parses the log file at `path` (the source is the path as given).
/// Throws InputError when the file cannot be read or is malformed.
DemoLog ReadDemoLog(const std::filesystem::path& path);

/// The text of `log` in format v1: the metadata (format, theta_deg, object_position, trial,
/// operator, sample_rate_hz, then the extra keys), the header and one row per sample. Numbers are
/// written in the shortest form that reads back to the identical double. Wrist quaternions are
/// written sign-normalized (w >= 0; q and -q are the same orientation) and unit (divided by their
/// norm unless that is already within 1e-15 of 1), so reading the text back gives every value
/// bit for bit, and formatting what was read gives the same text.
/// Throws InputError (naming `log.source`) when the result would not pass the reader's rules,
/// e.g. a time that does not increase or a missing grasp event.
std::string FormatDemoLog(const DemoLog& log);

/// Writes FormatDemoLog(log) to `path` atomically (temporary file + rename).
/// Throws InputError when the log breaks the format's rules (nothing is written then) or the file
/// cannot be written.
void WriteDemoLog(const std::filesystem::path& path, const DemoLog& log);

}  // namespace graspsynth
