// graspsynth run: the main job. Until the synthesis pipeline exists it runs the kinematics
// study that everything later stands on: for each object orientation of the paper, the wrist
// pose of the paper's Table I grasp in the shipped scene (models/scene.json), its feasible
// arm-angle set on the elbow-up branch, a solution in the middle of the widest feasible arc, and
// the forward-kinematics check of that solution.

#include "apps/run_command.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/scene_model.hpp"

namespace graspsynth::apps {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The paper's Table I grasp positions (d in metres, eta in degrees, object-centred polar
// coordinates of the wrist in the table plane), per object orientation theta.
struct TableRow {
  double theta_deg, d, eta_deg;
};
constexpr TableRow kTableI[] = {{20, 0.378, -75.3}, {30, 0.371, -73.0}, {40, 0.358, -71.1},
                                {50, 0.350, -69.0}, {60, 0.345, -63.1}, {70, 0.337, -59.2},
                                {80, 0.329, -57.3}, {90, 0.326, -47.1}, {100, 0.321, -40.6}};

// wrist height above the table for a grasp of the handle (reference/scene.md: 0.08-0.11 m).
constexpr double kWristHeight = 0.095;

// Wrist (hand-mount) pose for a grasp: palm down (x_H = -z_W), the hand's long axis z_H
// horizontal, across the handle and pointing from the wrist toward the handle's line.
Eigen::Isometry3d GraspWristPose(const SceneModel& scene, const TableRow& row) {
  const double eta = row.eta_deg * kDeg;
  const Eigen::Vector2d p_OW = row.d * Eigen::Vector2d(std::cos(eta), std::sin(eta));
  const Eigen::Vector2d handle = scene.ObjectPose(row.theta_deg * kDeg).linear().col(0).head<2>();
  Eigen::Vector2d toward = p_OW.dot(handle) * handle - p_OW;  // foot of the perpendicular
  if (toward.norm() < 1e-6) toward = Eigen::Vector2d(-handle.y(), handle.x());
  toward.normalize();
  Eigen::Matrix3d R;
  R.col(0) = -Eigen::Vector3d::UnitZ();
  R.col(2) = Eigen::Vector3d(toward.x(), toward.y(), 0.0);
  R.col(1) = R.col(2).cross(R.col(0));
  Eigen::Isometry3d X_WH = Eigen::Isometry3d::Identity();
  X_WH.linear() = R;
  X_WH.translation() << scene.object.centre_xy + p_OW, scene.table.top_z + kWristHeight;
  return X_WH;
}

struct RunOptions {
  std::string robot;
  std::string scene;
};

int RunKinematicsStudy(const RunOptions& opts) {
  const RobotModel robot = LoadRobotModel(opts.robot.empty() ? DefaultRobotDescriptionPath()
                                                             : std::filesystem::path(opts.robot));
  const SceneModel scene = LoadSceneModel(opts.scene.empty() ? DefaultSceneModelPath()
                                                             : std::filesystem::path(opts.scene));
  const ArmModel& arm = robot.arm;
  const SrsLengths& l = arm.lengths();
  std::printf("graspsynth run: kinematics study (the synthesis pipeline is not built yet)\n");
  std::printf("robot: %s\n", robot.source.c_str());
  std::printf(
      "  PA-10 SRS lengths from the description: d_bs %.3f  d_se %.3f  d_ew %.3f  "
      "d_wt %.3f m\n",
      l.d_bs, l.d_se, l.d_ew, l.d_wt);
  std::printf("  hand mount: %.3f m beyond the flange\n", robot.X_FH.translation().norm());
  std::printf("scene: %s\n", scene.source.c_str());
  std::printf(
      "\nPaper Table I grasp wrist positions (object centre at (%.2f, %.2f) m, wrist "
      "%.3f m above the table, branch GC2 = GC4 = GC6 = +1):\n\n",
      scene.object.centre_xy.x(), scene.object.centre_xy.y(), kWristHeight);
  std::printf(" theta  d_G    eta_G  | feasible psi (deg)     width | E1 at mid-psi  FK error\n");
  std::printf("  deg    m      deg   |                         deg  |     deg           m\n");
  int failures = 0;
  for (const TableRow& row : kTableI) {
    const Eigen::Isometry3d X_WF = GraspWristPose(scene, row) * robot.X_FH.inverse();
    const ArmTargetForm form = PrepareArmTarget(arm, X_WF, +1);
    const std::vector<Interval> feasible = FeasibleArmAngles(arm, form, +1, +1);
    double width = 0.0;
    for (const Interval& iv : feasible) width += iv.width();
    const std::optional<Interval> widest = WidestInterval(feasible);
    if (!widest) {
      ++failures;
      std::printf(" %5.0f  %.3f  %6.1f  | unreachable: %s\n", row.theta_deg, row.d, row.eta_deg,
                  std::string(ToString(form.status)).c_str());
      continue;
    }
    const double psi = 0.5 * (widest->lo + widest->hi);
    const ArmIkSolution s = SolveArmIk(arm, X_WF, psi, ArmBranch{});
    const double err = DistanceBetween(ArmFlangePose(arm, s.q), X_WF).translation;
    failures += s.status != IkStatus::kOk;
    std::printf(" %5.0f  %.3f  %6.1f  | [%6.1f, %6.1f]%s  %5.1f |   %6.1f       %.1e\n",
                row.theta_deg, row.d, row.eta_deg, widest->lo / kDeg, widest->hi / kDeg,
                feasible.size() > 1 ? "+" : " ", width / kDeg, s.q[3] / kDeg, err);
  }
  std::printf("\n%d of %zu orientations reachable within the joint limits.\n",
              static_cast<int>(std::size(kTableI)) - failures, std::size(kTableI));
  return failures == 0 ? 0 : 1;
}

}  // namespace

void AddRunCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* run = app.add_subcommand(
      "run",
      "The main job on the shipped defaults. For now: the kinematics study of the paper's\n"
      "Table I grasps (reachability and feasible arm angles of each wrist pose).");
  run->add_option("--robot", opts->robot, "Robot description (URDF); default: the shipped one");
  run->add_option("--scene", opts->scene, "Scene description (JSON); default: models/scene.json");
  run->callback([opts, exit_code] { *exit_code = RunKinematicsStudy(*opts); });
}

}  // namespace graspsynth::apps
