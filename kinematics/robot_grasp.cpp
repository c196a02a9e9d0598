#include "kinematics/robot_grasp.hpp"

#include <string>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "kinematics/robot_description.hpp"

namespace graspsynth {
namespace {

// the slack of the limit check: a shape at a joint's limit in degrees may land an ulp beyond it.
constexpr double kLimitSlack = 1e-6;

HandVector ReadShape(const JsonReader& shape, const HandModel& hand) {
  shape.AsObject();
  HandVector f = HandVector::Zero();
  for (const std::string& name : shape.Keys()) {
    const JsonReader angle = shape.Field(name);
    int k = 0;
    while (k < kHandDof && hand.actuated_names()[k] != name) ++k;
    if (k == kHandDof) {
      std::string names;
      for (const std::string& n : hand.actuated_names()) names += (names.empty() ? "" : ", ") + n;
      angle.Fail("an actuated joint of the hand (" + names + ")");
    }
    f[k] = angle.AsNumber() * kDeg;
    if (!(f[k] >= hand.lower()[k] - kLimitSlack && f[k] <= hand.upper()[k] + kLimitSlack)) {
      angle.Fail("an angle within " + name + "'s limits [" +
                 std::to_string(hand.lower()[k] / kDeg) + ", " +
                 std::to_string(hand.upper()[k] / kDeg) + "] deg");
    }
  }
  return f;
}

}  // namespace

RobotGrasp ReadRobotGrasp(const JsonReader& grasp, const HandModel& hand) {
  grasp.AsObject();
  grasp.RejectUnknownKeys({"comment", "bar_in_hand_m", "open_deg", "closed_deg"});
  RobotGrasp out;
  out.bar_in_hand = grasp.Numbers("bar_in_hand_m", 3, -0.5, 0.5);
  out.open = ReadShape(grasp.Field("open_deg"), hand);
  out.closed = ReadShape(grasp.Field("closed_deg"), hand);
  return out;
}

std::optional<RobotGrasp> LoadRobotGrasp(const std::filesystem::path& path, const HandModel& hand) {
  const JsonReader top = JsonReader::Parse(
      ReadInputFile(path, InputFileKind{"robot file", input_kind::kJsonBytes}), path.string());
  top.AsObject();
  if (!top.Has("grasp")) return std::nullopt;
  return ReadRobotGrasp(top.Field("grasp"), hand);
}

RobotGrasp RobotGraspOf(const RobotModel& robot) {
  if (robot.grasp) return *robot.grasp;
  const std::filesystem::path shipped = DataDirectory() / "models" / (robot.name + ".robot.json");
  std::optional<RobotGrasp> grasp;
  if (!robot.name.empty() && std::filesystem::is_regular_file(shipped)) {
    grasp = LoadRobotGrasp(shipped, robot.hand);
  }
  if (!grasp) {
    throw InputError(robot.source + ": robot '" + robot.name +
                     "' has no scripted grasp: its robot file needs a 'grasp' part (hand shapes "
                     "and bar_in_hand_m; docs/formats.md, 'Robot file')");
  }
  return *grasp;
}

}  // namespace graspsynth
