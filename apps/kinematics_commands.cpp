// graspsynth fk / ik: line-oriented forward and inverse kinematics of the arm. One JSON object
// per input line on stdout; a malformed line gets {"error": ...} on stdout, its line number on
// stderr, and the next line is read. graspsynth robots: the shipped robots.

#include "apps/kinematics_commands.hpp"

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/input_file.hpp"
#include "common/text_input.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/arm_reach.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
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

// What a command makes of one input line: its JSON object, a warning for stderr ("" for none),
// and whether the line is a result that failed (the exit status is then 1).
struct LineResult {
  json out;
  std::string warning;
  bool failed = false;
};

// Calls `handle(line_text)` (a LineResult) for every non-blank, non-comment line of the input,
// prints each line's JSON on stdout and its warning on stderr with the line's place, and reports
// malformed lines; returns the number of malformed or failed lines.
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
    const std::string place = source + ":" + std::to_string(number) + ": ";
    try {
      const LineResult result = handle(text);
      if (!result.warning.empty()) std::cerr << "graspsynth: " << place << result.warning << "\n";
      if (result.failed) ++bad;
      std::cout << result.out.dump() << "\n";
    } catch (const InputError& e) {
      ++bad;
      const std::string message = place + e.what();
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

// "limits [-1.641, 1.641] rad, [-94, 94] deg": joint i's limits.
std::string LimitText(const ArmModel& arm, int i) {
  const double lo = arm.lower()[i], hi = arm.upper()[i];
  return "limits [" + FixedNumber(lo, 3) + ", " + FixedNumber(hi, 3) + "] rad, [" +
         FixedNumber(lo * 180.0 / M_PI, 0) + ", " + FixedNumber(hi * 180.0 / M_PI, 0) + "] deg";
}

// Configuration q checked against the arm's joint limits: "within_limits" and, when some joint
// is outside, "outside_limits" (each joint's name, value and limits) in `*result`, and a warning
// naming them, with a hint at degrees when q read as degrees is within the limits and some value
// is beyond pi (no angle of a radian configuration of this arm needs more than its limits).
void CheckJointLimits(const ArmModel& arm, const Vector7d& q, LineResult* result) {
  json outside = json::array();
  std::string joints;
  for (int i = 0; i < kArmDof; ++i) {
    if (q[i] >= arm.lower()[i] && q[i] <= arm.upper()[i]) continue;
    const std::string& name = arm.joint(i).name;
    outside.push_back(
        {{"joint", name}, {"value", q[i]}, {"lower", arm.lower()[i]}, {"upper", arm.upper()[i]}});
    joints += (joints.empty() ? "" : ", ") + name + " = " + ShortestNumber(q[i]) + " (" +
              LimitText(arm, i) + ")";
  }
  result->out["within_limits"] = outside.empty();
  if (outside.empty()) return;
  result->out["outside_limits"] = outside;
  result->warning = "outside the joint limits: " + joints;
  const bool beyond_pi = q.cwiseAbs().maxCoeff() > M_PI;
  if (beyond_pi && arm.WithinLimits(q * (M_PI / 180.0))) {
    result->warning +=
        " (the values look like degrees: fk takes radians, and read as degrees they are within "
        "the limits)";
  }
}

LineResult FkLine(const ArmModel& arm, std::string_view text) {
  const std::vector<double> v = ParseLine(text, kArmDof, "q1 .. q7 in radians");
  const Vector7d q = Eigen::Map<const Vector7d>(v.data());
  const Eigen::Isometry3d X_WF = ArmFlangePose(arm, q);
  const Eigen::Quaterniond quat = Canonical(Eigen::Quaterniond(X_WF.linear()));
  const Eigen::Vector3d& p = X_WF.translation();
  LineResult result;
  result.out = json{{"position", {p.x(), p.y(), p.z()}},
                    {"quaternion", {quat.w(), quat.x(), quat.y(), quat.z()}}};
  CheckJointLimits(arm, q, &result);
  return result;
}

// The branch of the request, or none for all.
std::optional<ArmBranch> BranchOf(const request::IkRequest& r) {
  if (!r.branch) return std::nullopt;
  return ArmBranch{(*r.branch)[0], (*r.branch)[1], (*r.branch)[2]};
}

// "out of reach: ..." for a target whose wrist centre lies outside the arm's span, with a hint at
// millimetres when the target is farther than ten times the span (no workspace in metres is)
// and the position read as millimetres is within it.
std::string OutOfReachText(const ArmModel& arm, const Eigen::Isometry3d& X_WF) {
  const ArmReach reach = ReachOfTarget(arm, X_WF);
  std::string text = "out of reach: the wrist centre is " + FixedNumber(reach.distance, 3) +
                     " m from the shoulder, and the arm reaches from " +
                     FixedNumber(reach.inner, 3) + " to " + FixedNumber(reach.outer, 3) + " m";
  Eigen::Isometry3d X_WF_mm = X_WF;
  X_WF_mm.translation() /= 1000.0;
  const ArmReach mm = ReachOfTarget(arm, X_WF_mm);
  if (reach.distance > 10.0 * reach.outer && mm.distance >= mm.inner && mm.distance <= mm.outer) {
    text += " (the position looks like millimetres: ik takes metres)";
  }
  return text;
}

// The message of a reachable target without a solution at psi: the feasible arm angles, or why
// there are none.
std::string NoSolutionText(double psi, const json& psi_intervals) {
  std::string text = "no solution within the joint limits at psi = " + ShortestNumber(psi);
  if (psi_intervals.empty()) return text + " (no arm angle is feasible for this target)";
  text += " (feasible arm angles:";
  for (const json& iv : psi_intervals) {
    text += " [" + FixedNumber(iv[0].get<double>(), 3) + ", " +
            FixedNumber(iv[1].get<double>(), 3) + "]";
  }
  return text + ")";
}

LineResult IkLine(const ArmModel& arm, std::optional<ArmBranch> only, std::string_view text) {
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
  bool unreachable = true;  // on every branch considered (reach does not depend on the branch)
  for (int index = 0; index < 8; ++index) {
    const ArmBranch b = ArmBranch::FromIndex(index);
    if (only && !(b == *only)) continue;
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, b.gc4);
    unreachable &= form.status == IkStatus::kUnreachable;
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
  LineResult result;
  result.out = json{{"solutions", solutions},
                    {"psi_intervals", psi_intervals},
                    {"branches", branches},
                    {"status", "ok"}};
  if (!solutions.empty()) return result;
  result.failed = true;
  if (unreachable) {
    const ArmReach reach = ReachOfTarget(arm, X_WF);
    result.out["status"] = "out_of_reach";
    result.out["reach"] = {
        {"distance", reach.distance}, {"inner", reach.inner}, {"outer", reach.outer}};
    result.warning = OutOfReachText(arm, X_WF);
  } else {
    result.out["status"] = "no_solution";
    result.warning = NoSolutionText(psi, psi_intervals);
  }
  result.out["message"] = result.warning;
  return result;
}

void AddCommonOptions(CLI::App* cmd, KinematicsOptions* opts) {
  cmd->add_option("input", opts->input, "Input file, or - for standard input")
      ->capture_default_str();
  AddRobotOption(cmd, &opts->robot, " (of a robot file only its arm is read)");
}

// fk and ik need only the arm: from the URDF's whole robot, or from a robot file's arm part.
ArmModel LoadArm(const KinematicsOptions& opts) {
  if (opts.robot.empty()) return LoadRobotModel(DefaultRobotDescriptionPath()).arm;
  const std::filesystem::path path = ResolveRobotPath(opts.robot);
  if (path.extension() == ".json") return LoadArmFromRobotFile(path);
  return LoadRobotModel(path).arm;
}

// `graspsynth robots`: one line per shipped robot (its name, the default marked, and its
// comment), or their JSON array.
void ListRobots(bool as_json) {
  const std::vector<ShippedRobot> robots = ShippedRobots();
  json list = json::array();
  for (const ShippedRobot& robot : robots) {
    const std::string file = DataRelativeName(robot.file);
    if (as_json) {
      list.push_back({{"name", robot.name},
                      {"file", file},
                      {"default", robot.name == kDefaultRobotName},
                      {"comment", robot.comment}});
      continue;
    }
    std::cout << robot.name << (robot.name == kDefaultRobotName ? " (default)" : "") << "\n"
              << "  " << file << "\n";
    if (!robot.comment.empty()) std::cout << "  " << robot.comment << "\n";
  }
  if (as_json) std::cout << list.dump(2) << "\n";
}

}  // namespace

void AddKinematicsCommands(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<KinematicsOptions>();

  CLI::App* fk = app.add_subcommand(
      "fk",
      "Forward kinematics of the arm: the flange pose of each configuration\n"
      "Reads one configuration per line, 7 joint values in radians (S1 S2 S3 E1 E2 W1 W2,\n"
      "blank- or comma-separated), and prints one JSON object per line:\n"
      "  {\"position\":[x,y,z],\"quaternion\":[w,x,y,z],\"within_limits\":true}\n"
      "(flange pose, world frame, metres). A configuration outside the joint limits is still\n"
      "answered, with \"within_limits\":false and \"outside_limits\" (each joint's name, value,\n"
      "lower and upper limit), and named on stderr (with a hint when the values look like\n"
      "degrees). Blank lines and lines starting with # are skipped. A malformed line prints\n"
      "{\"error\":...} and is named on stderr; the exit status is 1 if any line was bad.\n"
      "Example:\n"
      "  echo \"0 0.5 0 1.2 0 0.6 0\" | graspsynth fk");
  AddCommonOptions(fk, opts.get());
  fk->callback([opts, exit_code] {
    const ArmModel arm = LoadArm(*opts);
    const int bad =
        ForEachInputLine(opts->input, [&](std::string_view text) { return FkLine(arm, text); });
    if (bad > 0) *exit_code = 1;
  });

  CLI::App* ik = app.add_subcommand(
      "ik",
      "Analytic inverse kinematics of the arm at a given arm angle\n"
      "Reads one flange target per line: x y z qw qx qy qz psi (metres, unit quaternion,\n"
      "arm angle in radians in [-pi, pi]) and prints one JSON object per line:\n"
      "  {\"solutions\":[[q1..q7],...],\"branches\":[...],\"psi_intervals\":[[lo,hi],...],\n"
      "   \"status\":\"ok\"}\n"
      "solutions: every solution within the joint limits at that psi over all 8 branches\n"
      "(or the --branch one); branches: the (GC2,GC4,GC6) signs of each solution (of its\n"
      "DH values: on an arm whose joint turns against the DH table, e.g. the iiwa's A4, the\n"
      "sign of that joint's negated value);\n"
      "psi_intervals: the arm angles at which the target is feasible (union over the\n"
      "branches considered). A target without a solution has status \"out_of_reach\" (its wrist\n"
      "centre beyond the arm's span from the shoulder: \"reach\" gives the distance and the span,\n"
      "with a hint when the position looks like millimetres) or \"no_solution\" (reachable, but\n"
      "not within the joint limits at that psi), a \"message\" that stderr repeats, and the exit\n"
      "status is 1. A malformed line prints {\"error\":...}; exit status 1 then too.\n"
      "Example:\n"
      "  echo \"0.5 0.2 0.6 0 1 0 0 0.3\" | graspsynth ik");
  AddCommonOptions(ik, opts.get());
  auto flags = std::make_shared<RequestFlags<request::IkRequest>>(ik, request::IkOptions());
  ik->callback([opts, flags, exit_code] {
    const std::optional<ArmBranch> only = BranchOf(flags->Build());
    const ArmModel arm = LoadArm(*opts);
    const int bad = ForEachInputLine(
        opts->input, [&](std::string_view text) { return IkLine(arm, only, text); });
    if (bad > 0) *exit_code = 1;
  });

  auto as_json = std::make_shared<bool>(false);
  CLI::App* robots = app.add_subcommand(
      "robots",
      "List the shipped robots: the names that --robot takes\n"
      "Each robot is a robot file, models/NAME.robot.json (graspsynth-robot/1, docs/formats.md),\n"
      "beside its URDF. Prints each robot's name, its file (relative to the data folder) and what\n"
      "it is; --json prints them as a JSON array of {name, file, default, comment}.\n"
      "Example:\n"
      "  graspsynth robots");
  robots->add_flag("--json", *as_json, "Print a JSON array instead of text");
  robots->callback([as_json] { ListRobots(*as_json); });
}

}  // namespace graspsynth::apps
