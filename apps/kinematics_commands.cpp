// graspsynth fk / ik: line-oriented forward and inverse kinematics of the arm. One JSON object
// per input line on stdout; a malformed line gets {"error": ...} on stdout, its line number on
// stderr, and the next line is read.

#include "apps/kinematics_commands.hpp"

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "apps/request_flags.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/text_input.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_description.hpp"
#include "request/kinematics_request.hpp"

namespace graspsynth::apps {
namespace {

using nlohmann::json;

// Tolerance on |q| - 1 for an input quaternion; within it the quaternion is normalized.
constexpr double kQuaternionTol = 1e-6;

struct KinematicsOptions {
  std::string input = "-";
  std::string robot;
};

// The longest input line taken (a line of 7 or 8 numbers has well under 1 KiB).
constexpr size_t kMaxLineBytes = 64 * 1024;
// An input file of lines (a regular file only, at most this size: about a million lines).
constexpr InputFileKind kLinesFile{"input file", 256 * input_kind::kMiB};

// Reads the next line of `in` into `line`, at most kMaxLineBytes of it. False at the end of the
// input; throws InputError naming `source` and the line for a longer line (an endless stream
// such as /dev/zero on standard input ends there, not in memory).
bool NextLine(std::istream& in, const std::string& source, int number, std::string* line) {
  line->clear();
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get()) {
    if (c == '\n') return true;
    if (line->size() == kMaxLineBytes) {
      throw InputError(source + ":" + std::to_string(number) + ": the line is longer than " +
                       std::to_string(kMaxLineBytes) + " bytes (one configuration or pose a line)");
    }
    line->push_back(static_cast<char>(c));
  }
  return !line->empty();
}

// Calls `handle(line_text)` for every non-blank, non-comment line of the input and reports
// malformed lines; returns the number of malformed lines.
template <typename Handler>
int ForEachInputLine(const std::string& input, Handler handle) {
  std::istringstream file;
  std::istream* in = &std::cin;
  if (input != "-") {
    file.str(ReadInputFile(input, kLinesFile));
    in = &file;
  }
  const std::string source = input == "-" ? "<stdin>" : input;
  int bad = 0;
  std::string line;
  for (int number = 1; NextLine(*in, source, number, &line); ++number) {
    const std::string_view text = TrimBlanks(line);
    if (text.empty() || text.front() == '#') continue;
    try {
      std::cout << handle(text).dump() << "\n";
    } catch (const InputError& e) {
      ++bad;
      const std::string message = source + ":" + std::to_string(number) + ": " + e.what();
      std::cerr << "graspsynth: " << message << "\n";
      std::cout << json{{"error", message}}.dump() << "\n";
    }
  }
  std::cout.flush();
  return bad;
}

std::vector<double> ParseLine(std::string_view text, size_t count, const char* layout) {
  std::string why;
  const auto values = ParseNumberList(text, count, &why);
  if (!values) throw InputError(why + " (expected: " + layout + ")");
  return *values;
}

json ToJson(const Vector7d& q) { return std::vector<double>(q.data(), q.data() + kArmDof); }

json FkLine(const ArmModel& arm, std::string_view text) {
  const std::vector<double> v = ParseLine(text, kArmDof, "q1 .. q7 in radians");
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, Eigen::Map<const Vector7d>(v.data()));
  const Eigen::Quaterniond q = Canonical(Eigen::Quaterniond(X_WF.linear()));
  const Eigen::Vector3d& p = X_WF.translation();
  return json{{"position", {p.x(), p.y(), p.z()}}, {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

// The branch of the request, or none for all.
std::optional<ArmBranch> BranchOf(const request::IkRequest& r) {
  if (!r.branch) return std::nullopt;
  return ArmBranch{(*r.branch)[0], (*r.branch)[1], (*r.branch)[2]};
}

json IkLine(const ArmModel& arm, std::optional<ArmBranch> only, std::string_view text) {
  const std::vector<double> v = ParseLine(text, 8, "x y z qw qx qy qz psi");
  Eigen::Quaterniond quat(v[3], v[4], v[5], v[6]);
  if (std::abs(quat.norm() - 1.0) > kQuaternionTol) {
    throw InputError("quaternion (qw qx qy qz) has norm " + std::to_string(quat.norm()) +
                     ", not 1");
  }
  const double psi = v[7];
  if (psi < -M_PI - 1e-12 || psi > M_PI + 1e-12) {
    throw InputError("psi = " + std::to_string(psi) + " is outside [-pi, pi]");
  }
  Eigen::Isometry3d X_WF = PoseFrom(Eigen::Vector3d(v[0], v[1], v[2]), quat.normalized());

  json solutions = json::array();
  json branches = json::array();
  std::vector<Interval> intervals;
  for (int index = 0; index < 8; ++index) {
    const ArmBranch b = ArmBranch::FromIndex(index);
    if (only && !(b == *only)) continue;
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
    const std::vector<Interval> feasible = FeasibleArmAngles(arm, form, b.gc2, b.gc6);
    intervals.insert(intervals.end(), feasible.begin(), feasible.end());
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, b);
    if (s.status == IkStatus::kOk) {
      solutions.push_back(ToJson(s.q));
      branches.push_back({b.gc2, b.gc4, b.gc6});
    }
  }
  json psi_intervals = json::array();
  for (const Interval& iv : MergeIntervals(intervals)) psi_intervals.push_back({iv.lo, iv.hi});
  return json{{"solutions", solutions}, {"psi_intervals", psi_intervals}, {"branches", branches}};
}

void AddCommonOptions(CLI::App* cmd, KinematicsOptions* opts) {
  cmd->add_option("input", opts->input, "Input file, or - for standard input")
      ->capture_default_str();
  cmd->add_option("--robot", opts->robot,
                  "Robot description (URDF); default: models/pa10_gifu3.urdf of this checkout "
                  "or $GRASPSYNTH_DATA_DIR/models/pa10_gifu3.urdf");
}

RobotModel LoadRobot(const KinematicsOptions& opts) {
  return LoadRobotModel(opts.robot.empty() ? DefaultRobotDescriptionPath()
                                           : std::filesystem::path(opts.robot));
}

}  // namespace

void AddKinematicsCommands(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<KinematicsOptions>();

  CLI::App* fk = app.add_subcommand(
      "fk",
      "Forward kinematics of the arm.\n"
      "Reads one configuration per line, 7 joint values in radians (S1 S2 S3 E1 E2 W1 W2,\n"
      "blank- or comma-separated), and prints one JSON object per line:\n"
      "  {\"position\":[x,y,z],\"quaternion\":[w,x,y,z]}  (flange pose, world frame, metres)\n"
      "Blank lines and lines starting with # are skipped. A malformed line prints\n"
      "{\"error\":...} and is named on stderr; the exit status is 1 if any line was bad.");
  AddCommonOptions(fk, opts.get());
  fk->callback([opts, exit_code] {
    const RobotModel robot = LoadRobot(*opts);
    const int bad = ForEachInputLine(
        opts->input, [&](std::string_view text) { return FkLine(robot.arm, text); });
    if (bad > 0) *exit_code = 1;
  });

  CLI::App* ik = app.add_subcommand(
      "ik",
      "Analytic inverse kinematics of the arm at a given arm angle.\n"
      "Reads one flange target per line: x y z qw qx qy qz psi (metres, unit quaternion,\n"
      "arm angle in radians in [-pi, pi]) and prints one JSON object per line:\n"
      "  {\"solutions\":[[q1..q7],...],\"psi_intervals\":[[lo,hi],...],\"branches\":[...]}\n"
      "solutions: every solution within the joint limits at that psi over all 8 branches\n"
      "(or the --branch one); branches: the (GC2,GC4,GC6) signs of each solution;\n"
      "psi_intervals: the arm angles at which the target is feasible (union over the\n"
      "branches considered). A malformed line prints {\"error\":...}; exit status 1 then.");
  AddCommonOptions(ik, opts.get());
  auto flags = std::make_shared<RequestFlags<request::IkRequest>>(ik, request::IkOptions());
  ik->callback([opts, flags, exit_code] {
    const std::optional<ArmBranch> only = BranchOf(flags->Build());
    const RobotModel robot = LoadRobot(*opts);
    const int bad = ForEachInputLine(
        opts->input, [&](std::string_view text) { return IkLine(robot.arm, only, text); });
    if (bad > 0) *exit_code = 1;
  });
}

}  // namespace graspsynth::apps
