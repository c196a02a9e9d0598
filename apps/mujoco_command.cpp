// graspsynth export-mjcf: the grasp scene as an MJCF model (simulation_mujoco/mjcf_export.hpp).

#include "apps/mujoco_command.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "gate/grasp_file.hpp"
#include "kinematics/robot_file.hpp"
#include "request/mujoco_request.hpp"
#include "scene/base_frame.hpp"

namespace graspsynth::apps {
namespace {

// The command's own options; the model's are the request's (request/mujoco_request.hpp).
struct ExportOptions {
  std::string out;
  std::string trajectory;
  std::string robot;
  std::string scene;
  std::string object;
};

int RunExportMjcf(const ExportOptions& o, const request::ExportMjcfRequest& r) {
  const MjcfOptions options = request::ToMjcfOptions(r);  // every option checked first
  const SimulationModel model(LoadRobotOption(o.robot), LoadScene(o.scene, o.object));
  std::optional<JointTrajectory> trajectory;
  Placement placement;
  if (!o.trajectory.empty()) {
    RequireDefaultRobot(model.robot(), "--robot: export-mjcf",
                        "a trajectory or grasp file (graspsynth-trajectory/1, graspsynth-grasp/1)");
    // a graspsynth-trajectory/1 file, or the "trajectory" member of a graspsynth-grasp/1 file.
    trajectory = LoadTrajectoryOrGraspFile(o.trajectory, model.robot().arm, model.robot().hand);
    PlaceTrajectoryObject(model.scene(), r.at, o.trajectory, &*trajectory);
    placement = trajectory->placement();
  } else if (r.at) {
    placement.xy = TablePointInScene(model.scene(), *r.at);
    try {
      model.scene().CheckOnTable(*placement.xy);
    } catch (const InputError& e) {
      throw InputError(std::string("--at: ") + e.what());
    }
  }
  if (r.theta) placement.theta = Radians(*r.theta);
  if (trajectory && r.theta && *r.theta != trajectory->theta_deg) {
    std::cerr << "note: --theta " << *r.theta << " deg differs from the trajectory's "
              << trajectory->theta_deg << " deg: the keyframes were made for the latter\n";
  }
  const MjcfModel mjcf = ExportMjcf(model, placement, options, trajectory ? &*trajectory : nullptr);
  WriteFileAtomically(o.out, mjcf.xml);
  std::cerr << "wrote " << o.out << ": " << mjcf.geoms.size() << " collision geoms"
            << (trajectory ? ", " + std::to_string(trajectory->samples.size()) + " keyframes" : "")
            << "\n";
  return 0;
}

}  // namespace

void AddExportMjcfCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand(
      "export-mjcf",
      "Write the robot, table and object (and a grasp) as an MJCF model for MuJoCo\n"
      "The PA-10 arm and the Gifu Hand III of the robot description, with a servo for every joint "
      "(the description's limits and\n"
      "force caps), the table, and the object (primitives; meshes as mesh assets) at --theta\n"
      "and --at, with the contact settings that mirror graspsynth's ODE world. With\n"
      "--trajectory (graspsynth-trajectory/1 or graspsynth-grasp/1) the placement is the\n"
      "trajectory's and each of its samples becomes a keyframe (time, qpos, ctrl = the\n"
      "servos' targets) that a MuJoCo user plays by holding each key's ctrl from its time.\n"
      "Names, gains and the contact mapping: docs/mujoco.md. Exit status: 0, or 2 on bad input.\n\n"
      "Examples:\n"
      "  graspsynth export-mjcf --theta 45 --out pan45.xml\n"
      "  graspsynth export-mjcf --trajectory examples/grasp_60deg.json --out grasp60.xml");
  auto flags =
      std::make_shared<RequestFlags<request::ExportMjcfRequest>>(cmd, request::ExportMjcfOptions());
  cmd->add_option("--out", opts->out, "MJCF file to write")->required();
  cmd->add_option("--trajectory", opts->trajectory,
                  "Trajectory or grasp file whose samples become keyframes "
                  "(graspsynth-trajectory/1, graspsynth-grasp/1)")
      ->check(CLI::ExistingFile);
  AddRobotOption(cmd, &opts->robot);
  cmd->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  AddObjectFlag(cmd, &opts->object);
  cmd->callback([opts, flags, exit_code] { *exit_code = RunExportMjcf(*opts, flags->Build()); });
}

}  // namespace graspsynth::apps
