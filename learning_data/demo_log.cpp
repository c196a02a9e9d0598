#include "learning_data/demo_log.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <utility>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/input_file.hpp"
#include "common/text_input.hpp"
#include "kinematics/pose_math.hpp"

namespace graspsynth {
namespace {

// 0-based column indices of the blocks of a sample row.
constexpr int kColT = 0;
constexpr int kColWrist = 1;
constexpr int kColQuat = 4;
constexpr int kColFingers = 8;
constexpr int kColEvent = 24;
constexpr int kColObject = 25;

std::vector<std::string> MakeColumns() {
  std::vector<std::string> names = {"t",        "wrist_x",  "wrist_y",  "wrist_z",
                                    "wrist_qw", "wrist_qx", "wrist_qy", "wrist_qz"};
  for (int i = 0; i < kHandDof; ++i) {
    // appended rather than "f" + to_string(i), which trips GCC 12's -Wrestrict false positive.
    std::string name(1, 'f');
    name += std::to_string(i);
    names.push_back(std::move(name));
  }
  names.insert(names.end(), {"event", "object_x", "object_y", "object_z"});
  return names;
}

// "file:line: " prefix of a message.
std::string At(const std::string& source, size_t line) {
  return source + ":" + std::to_string(line) + ": ";
}

// "file:line: column k 'name': " prefix of a message about one field (k is 1-based).
std::string AtColumn(const std::string& source, size_t line, int column) {
  return At(source, line) + "column " + std::to_string(column + 1) + " '" + DemoColumns()[column] +
         "': ";
}

std::string Quoted(std::string_view text) { return "'" + std::string(text) + "'"; }

// One metadata line, already known to start with '#'.
struct MetadataLine {
  std::string key;
  std::string value;
};

MetadataLine ParseMetadataLine(std::string_view text, const std::string& source, size_t line) {
  std::string_view body = TrimBlanks(text.substr(1));
  const size_t colon = body.find(':');
  const std::string_view key =
      colon == std::string_view::npos ? "" : TrimBlanks(body.substr(0, colon));
  const bool key_ok = !key.empty() && key.find_first_of(" \t") == std::string_view::npos;
  if (!key_ok) {
    throw InputError(At(source, line) + "expected a metadata line '# key: value' before the " +
                     "header, got " + Quoted(text));
  }
  return {std::string(key), std::string(TrimBlanks(body.substr(colon + 1)))};
}

double ParseMetadataNumber(const MetadataLine& m, const std::string& source, size_t line) {
  const std::optional<double> value = ParseFiniteDouble(m.value);
  if (!value) {
    throw InputError(At(source, line) + "metadata '" + m.key +
                     "': not a finite number: " + Quoted(m.value));
  }
  return *value;
}

Eigen::Vector3d ParseMetadataPosition(const MetadataLine& m, const std::string& source,
                                      size_t line) {
  const std::vector<std::string_view> fields = SplitFields(m.value, ',');
  if (fields.size() != 3) {
    throw InputError(At(source, line) + "metadata '" + m.key + "': expected x,y,z (3 numbers), " +
                     "found " + std::to_string(fields.size()) + " fields in " + Quoted(m.value));
  }
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> value = ParseFiniteDouble(fields[i]);
    if (!value) {
      throw InputError(At(source, line) + "metadata '" + m.key + "': component " +
                       std::to_string(i + 1) + " is not a finite number: " + Quoted(fields[i]));
    }
    if (std::abs(*value) > kDemoMaxPosition) {
      throw InputError(At(source, line) + "metadata '" + m.key + "': component " +
                       std::to_string(i + 1) + " = " + Quoted(TrimBlanks(fields[i])) +
                       " m is beyond +-" + ShortestNumber(kDemoMaxPosition) + " m");
    }
    p[i] = *value;
  }
  return p;
}

// Collects the metadata lines into `metadata`; checks the required keys at the end.
class MetadataCollector {
 public:
  MetadataCollector(const std::string& source, DemoMetadata* metadata)
      : source_(source), metadata_(metadata) {}

  void Add(const MetadataLine& m, size_t line) {
    const auto [it, inserted] = lines_.emplace(m.key, line);
    if (!inserted) {
      throw InputError(At(source_, line) + "metadata '" + m.key +
                       "' appears twice (first on line " + std::to_string(it->second) + ")");
    }
    if (m.key == "format") {
      if (m.value != kDemoLogFormat) {
        throw InputError(At(source_, line) + "metadata 'format': expected " +
                         Quoted(kDemoLogFormat) + ", got " + Quoted(m.value));
      }
      metadata_->format = m.value;
    } else if (m.key == "theta_deg") {
      metadata_->theta_deg = ParseMetadataNumber(m, source_, line);
    } else if (m.key == "object_position") {
      metadata_->object_position = ParseMetadataPosition(m, source_, line);
    } else if (m.key == "trial") {
      metadata_->trial = m.value;
    } else if (m.key == "operator") {
      metadata_->operator_name = m.value;
    } else if (m.key == "sample_rate_hz") {
      const double rate = ParseMetadataNumber(m, source_, line);
      if (!(rate > 0.0)) {
        throw InputError(At(source_, line) + "metadata 'sample_rate_hz': must be > 0, got " +
                         Quoted(m.value));
      }
      metadata_->sample_rate_hz = rate;
    } else {
      metadata_->extra.emplace_back(m.key, m.value);
    }
  }

  void CheckRequired(size_t header_line) const {
    for (const char* key : {"format", "theta_deg", "object_position"}) {
      if (lines_.count(key) == 0) {
        throw InputError(At(source_, header_line) + "missing required metadata '# " + key +
                         ": ...' before the header");
      }
    }
  }

 private:
  const std::string& source_;
  DemoMetadata* metadata_;
  std::map<std::string, size_t> lines_;
};

void CheckHeader(std::string_view text, const std::string& source, size_t line) {
  const std::vector<std::string_view> fields = SplitFields(text, ',');
  const size_t common = std::min(fields.size(), DemoColumns().size());
  for (size_t i = 0; i < common; ++i) {
    const std::string_view name = TrimBlanks(fields[i]);
    if (name != DemoColumns()[i]) {
      throw InputError(At(source, line) + "header column " + std::to_string(i + 1) +
                       ": expected '" + DemoColumns()[i] + "', got " + Quoted(name) +
                       " (the header must be exactly: t, wrist_x, wrist_y, wrist_z, wrist_qw, "
                       "wrist_qx, wrist_qy, wrist_qz, f0 .. f15, event, object_x, object_y, "
                       "object_z)");
    }
  }
  if (fields.size() < DemoColumns().size()) {
    throw InputError(At(source, line) + "header has " + std::to_string(fields.size()) +
                     " columns, expected " + std::to_string(DemoColumns().size()) + ": column " +
                     std::to_string(fields.size() + 1) + " '" + DemoColumns()[fields.size()] +
                     "' is missing");
  }
  if (fields.size() > DemoColumns().size()) {
    throw InputError(At(source, line) + "header has " + std::to_string(fields.size()) +
                     " columns, expected " + std::to_string(DemoColumns().size()) + ": column " +
                     std::to_string(DemoColumns().size() + 1) + " " +
                     Quoted(TrimBlanks(fields[DemoColumns().size()])) + " is not in the format");
  }
}

DemoSample ParseSampleRow(std::string_view text, const std::string& source, size_t line) {
  const std::vector<std::string_view> fields = SplitFields(text, ',');
  const size_t n = DemoColumns().size();
  if (fields.size() < n) {
    throw InputError(At(source, line) + "expected " + std::to_string(n) + " fields, found " +
                     std::to_string(fields.size()) + ": column " +
                     std::to_string(fields.size() + 1) + " '" + DemoColumns()[fields.size()] +
                     "' is missing");
  }
  if (fields.size() > n) {
    throw InputError(At(source, line) + "expected " + std::to_string(n) + " fields, found " +
                     std::to_string(fields.size()) + ": column " + std::to_string(n + 1) +
                     " is beyond the last column 'object_z'");
  }
  double v[kDemoColumnCount];
  for (int i = 0; i < kDemoColumnCount; ++i) {
    const std::optional<double> value = ParseFiniteDouble(fields[i]);
    if (!value) {
      throw InputError(AtColumn(source, line, i) +
                       "not a finite number: " + Quoted(TrimBlanks(fields[i])));
    }
    // bounds far beyond any robot's, so that every sum and mean of the analysis stays finite.
    // (the quaternion and the event have no bound here: they are checked below.)
    const auto [bound, unit] = i == kColT ? std::pair{kDemoMaxTime, " s"}
                               : (i >= kColWrist && i < kColQuat) || i >= kColObject
                                   ? std::pair{kDemoMaxPosition, " m"}
                               : i >= kColFingers && i < kColEvent
                                   ? std::pair{kDemoMaxJoint, " rad"}
                                   : std::pair{std::numeric_limits<double>::infinity(), ""};
    if (std::abs(*value) > bound) {
      throw InputError(AtColumn(source, line, i) + Quoted(TrimBlanks(fields[i])) + " is beyond +-" +
                       ShortestNumber(bound) + unit);
    }
    v[i] = *value;
  }
  DemoSample s;
  s.t = v[kColT];
  s.p_WH = Eigen::Vector3d(v[kColWrist], v[kColWrist + 1], v[kColWrist + 2]);
  s.q_WH = Eigen::Quaterniond(v[kColQuat], v[kColQuat + 1], v[kColQuat + 2], v[kColQuat + 3]);
  for (int i = 0; i < kHandDof; ++i) s.f[i] = v[kColFingers + i];
  s.p_WO = Eigen::Vector3d(v[kColObject], v[kColObject + 1], v[kColObject + 2]);

  const double norm = s.q_WH.norm();
  if (std::abs(norm - 1.0) > kDemoQuaternionTolerance) {
    std::ostringstream why;
    why.precision(9);
    why << At(source, line) << "columns 5-8 'wrist_qw'..'wrist_qz': the quaternion (" << v[kColQuat]
        << ", " << v[kColQuat + 1] << ", " << v[kColQuat + 2] << ", " << v[kColQuat + 3]
        << ") has norm " << norm << ", not 1 (tolerance " << kDemoQuaternionTolerance << ")";
    throw InputError(why.str());
  }
  const double event = v[kColEvent];
  if (event != 0.0 && event != 1.0 && event != 2.0) {
    throw InputError(AtColumn(source, line, kColEvent) + "event must be 0, 1 or 2, got " +
                     Quoted(TrimBlanks(fields[kColEvent])));
  }
  s.event = static_cast<DemoEvent>(static_cast<int>(event));
  return s;
}

}  // namespace

const std::vector<std::string>& DemoColumns() {
  static const std::vector<std::string> columns = MakeColumns();
  return columns;
}

std::optional<size_t> FindEvent(const DemoLog& log, DemoEvent event) {
  for (size_t i = 0; i < log.samples.size(); ++i) {
    if (log.samples[i].event == event) return i;
  }
  return std::nullopt;
}

namespace {

// Where ParseDemoLog is in the file: 0 for a line not seen yet.
struct LogLines {
  std::vector<size_t> samples;  // file line of each sample
  size_t header = 0;
  size_t first_blank_after_data = 0;  // a blank line after the header (allowed only at the end)
  size_t grasp = 0;
  size_t end = 0;
};

// One line after the header (`body` trimmed): a sample row, or a blank at the end of the file.
void AddRowAfterHeader(std::string_view body, const std::string& source, size_t line,
                       LogLines* lines, DemoLog* log) {
  if (body.empty()) {
    if (lines->first_blank_after_data == 0) lines->first_blank_after_data = line;
    return;
  }
  if (lines->first_blank_after_data != 0) {
    throw InputError(At(source, lines->first_blank_after_data) +
                     "blank line between sample rows (only the end of the file may be blank)");
  }
  if (body.front() == '#') {
    throw InputError(At(source, line) + "comment or metadata line after the header (line " +
                     std::to_string(lines->header) + "); metadata must come before the header");
  }
  if (lines->end != 0) {
    throw InputError(At(source, line) + "sample after the end event on line " +
                     std::to_string(lines->end) + " (the end event must be the last row)");
  }
  DemoSample sample = ParseSampleRow(body, source, line);
  if (!log->samples.empty() && !(sample.t > log->samples.back().t)) {
    throw InputError(AtColumn(source, line, kColT) + "time " + ShortestNumber(sample.t) +
                     " s does not increase (the sample on line " +
                     std::to_string(lines->samples.back()) +
                     " has t = " + ShortestNumber(log->samples.back().t) + " s)");
  }
  if (sample.event == DemoEvent::kGrasp) {
    if (lines->grasp != 0) {
      throw InputError(AtColumn(source, line, kColEvent) +
                       "a second grasp event (1); the first is on line " +
                       std::to_string(lines->grasp) + " and there must be exactly one");
    }
    lines->grasp = line;
  } else if (sample.event == DemoEvent::kEnd) {
    lines->end = line;
  }
  log->samples.push_back(std::move(sample));
  lines->samples.push_back(line);
}

// The checks on the whole log once every line is read (`line`: the last line number).
void CheckComplete(const LogLines& lines, const DemoLog& log, const std::string& source,
                   size_t line, const MetadataCollector& metadata) {
  if (lines.header == 0) {
    metadata.CheckRequired(line);
    throw InputError(source + ": no header row (expected 't, wrist_x, ..., object_z' after the " +
                     "metadata)");
  }
  if (log.samples.empty()) {
    throw InputError(At(source, lines.header) + "no samples after the header");
  }
  const std::string last = At(source, lines.samples.back());
  if (lines.grasp == 0) {
    throw InputError(last + "column " + std::to_string(kColEvent + 1) +
                     " 'event': the log has no grasp event (1); exactly one is required");
  }
  if (lines.end == 0) {
    throw InputError(last + "column " + std::to_string(kColEvent + 1) +
                     " 'event': the last row is not an end event (2); the recording is "
                     "truncated");
  }
}

}  // namespace

DemoLog ParseDemoLog(std::string_view text, const std::string& source) {
  DemoLog log;
  log.source = source;
  // a UTF-8 byte-order mark, which some spreadsheet programs write, is not content.
  constexpr std::string_view kByteOrderMark = "\xEF\xBB\xBF";
  if (text.substr(0, kByteOrderMark.size()) == kByteOrderMark) {
    text.remove_prefix(kByteOrderMark.size());
  }
  if (TrimBlanks(text).empty()) throw InputError(source + ": empty file");

  MetadataCollector metadata(source, &log.metadata);
  LogLines lines;
  size_t line = 0;
  size_t pos = 0;
  while (pos < text.size()) {
    const size_t eol = std::min(text.find('\n', pos), text.size());
    const std::string_view body = TrimBlanks(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line;
    if (lines.header != 0) {
      AddRowAfterHeader(body, source, line, &lines, &log);
    } else if (body.empty()) {
      continue;
    } else if (body.front() == '#') {
      metadata.Add(ParseMetadataLine(body, source, line), line);
    } else {
      metadata.CheckRequired(line);
      CheckHeader(body, source, line);
      lines.header = line;
    }
  }
  CheckComplete(lines, log, source, line, metadata);
  return log;
}

DemoLog ReadDemoLog(const std::filesystem::path& path) {
  return ParseDemoLog(ReadInputFile(path, input_kind::kDemoLog), path.string());
}

namespace {

// FormatDemoLog with `source` naming the log in messages.
std::string FormatChecked(const DemoLog& log, const std::string& source) {
  const DemoMetadata& m = log.metadata;
  std::string out;
  out += "# format: " + m.format + "\n";
  out += "# theta_deg: " + ShortestNumber(m.theta_deg) + "\n";
  out += "# object_position: " + ShortestNumber(m.object_position.x()) + "," +
         ShortestNumber(m.object_position.y()) + "," + ShortestNumber(m.object_position.z()) + "\n";
  if (m.trial) out += "# trial: " + *m.trial + "\n";
  if (m.operator_name) out += "# operator: " + *m.operator_name + "\n";
  if (m.sample_rate_hz) out += "# sample_rate_hz: " + ShortestNumber(*m.sample_rate_hz) + "\n";
  for (const auto& [key, value] : m.extra) out += "# " + key + ": " + value + "\n";

  for (size_t i = 0; i < DemoColumns().size(); ++i) {
    out += (i == 0 ? "" : ",") + DemoColumns()[i];
  }
  out += "\n";
  for (size_t k = 0; k < log.samples.size(); ++k) {
    const DemoSample& s = log.samples[k];
    const double norm = s.q_WH.norm();
    if (!(std::abs(norm - 1.0) <= kDemoQuaternionTolerance)) {
      throw InputError(source + ": sample " + std::to_string(k) +
                       ": the wrist quaternion has norm " + ShortestNumber(norm) + ", not 1");
    }
    const Eigen::Quaterniond q = CanonicalForFile(s.q_WH);
    const auto add = [&out](double value) {
      out += ShortestNumber(value);
      out += ',';
    };
    add(s.t);
    for (int i = 0; i < 3; ++i) add(s.p_WH[i]);
    add(q.w());
    add(q.x());
    add(q.y());
    add(q.z());
    for (int i = 0; i < kHandDof; ++i) add(s.f[i]);
    out += std::to_string(static_cast<int>(s.event)) + ",";
    add(s.p_WO.x());
    add(s.p_WO.y());
    out += ShortestNumber(s.p_WO.z()) + "\n";
  }
  // the writer never produces a file its own reader would reject.
  ParseDemoLog(out, source);
  return out;
}

}  // namespace

std::string FormatDemoLog(const DemoLog& log) {
  return FormatChecked(log, log.source.empty() ? std::string("<demonstration log>") : log.source);
}

void WriteDemoLog(const std::filesystem::path& path, const DemoLog& log) {
  WriteFileAtomically(path, FormatChecked(log, path.string()));
}

}  // namespace graspsynth
