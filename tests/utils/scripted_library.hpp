#pragma once

/// @file
/// A small grasp library built in memory from scripted grasps (motion/scripted_grasp.hpp):
/// each entry's grasping motion runs from the scripted pre-grasp pose to the pose where the
/// fingers have closed on the handle (the demonstrations' grasp-button moment), wrist poses from
/// the arm's forward kinematics of the scripted joint samples.

#include <stdexcept>
#include <string>
#include <vector>

#include "kinematics/arm_model.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/scripted_grasp.hpp"

namespace graspsynth::testing {

/// One scripted grasp at theta_deg on `side` of the handle as a library entry; `base` gives
/// the other options of the scripted grasp.
inline LibraryEntry ScriptedEntry(const RobotModel& robot, const SceneModel& scene,
                                  double theta_deg, int side = +1,
                                  const ScriptedGraspOptions& base = {}) {
  ScriptedGraspOptions o = base;
  o.theta_deg = theta_deg;
  o.side = side;
  const ScriptedGraspResult r = BuildScriptedGrasp(robot, scene, o);
  if (!r.ok) throw std::runtime_error("scripted grasp failed: " + r.message);
  const std::vector<WristWaypoint>& marks = r.trajectory.waypoints;  // rest, pre, grasp, closed
  const double t_pre = marks[1].t, t_closed = marks[3].t;
  LibraryEntry e;
  e.theta_deg = theta_deg;
  e.file =
      "scripted_" + std::to_string(static_cast<int>(theta_deg)) + (side > 0 ? "r" : "l") + ".csv";
  e.trial = "scripted";
  e.score = 1.0;
  e.motion.theta = theta_deg * M_PI / 180.0;
  e.motion.p_WO = scene.ObjectPose(e.motion.theta).translation();
  e.motion.source = e.file;
  for (const TrajectorySample& s : r.trajectory.samples) {
    if (s.t < t_pre - 1e-9 || s.t > t_closed + 1e-9) continue;
    const Eigen::Isometry3d X = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
    MotionWaypoint w;
    w.t = s.t - t_pre;
    w.p_WH = X.translation();
    w.q_WH = Eigen::Quaterniond(X.linear()).normalized();
    w.f = s.hand;
    e.motion.waypoints.push_back(w);
  }
  e.lift_height = o.lift_height;
  e.lift_duration = o.lift_duration;
  return e;
}

/// A library of scripted grasps at `thetas` (deg, increasing), all on `side`.
inline GraspLibrary ScriptedLibrary(const RobotModel& robot, const SceneModel& scene,
                                    const std::vector<double>& thetas, int side = +1,
                                    const ScriptedGraspOptions& base = {}) {
  GraspLibrary library;
  library.demo_directory = "scripted";
  library.tie_rule = "none";
  for (double theta : thetas)
    library.entries.push_back(ScriptedEntry(robot, scene, theta, side, base));
  return library;
}

}  // namespace graspsynth::testing
