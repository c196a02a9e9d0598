#pragma once

/// @file
/// A demonstration log as the robot would play it: the logged wrist poses and finger joints,
/// sample by sample, through the analytic IK with a continuous arm angle (motion/joint_space.hpp)
/// into a joint trajectory that simulation/trial.hpp runs. The synthetic operator labels its
/// trials with it, and the representative selection replays each demonstration's reach,
/// grasping motion and lift with it.

#include <string>

#include "kinematics/robot_description.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/joint_space.hpp"

namespace graspsynth {

/// The joint trajectory of a log, or why there is none.
struct DemoReplay {
  bool ok = false;
  std::string message;  ///< why not, when !ok (names the log and the sample)
  /// Samples at the log's times (stretched where a joint would exceed its velocity cap), theta
  /// from the metadata, waypoints: the first sample, the grasp-event sample and the last one.
  JointTrajectory trajectory;
};

/// Converts `log`: the first wrist pose is solved with the arm angle in the middle of its widest
/// feasible arc (SolveArmIkMidArc) and the rest follow with a continuous arm angle on the same
/// branch. Branches are tried in the order elbow-up (+1, +1, +1), its wrist flip (+1, +1, -1),
/// then the others; the first on which every sample converts is used. When none does, the
/// result has ok = false and the first branch's failure (the sample, unreachable or a joint
/// jump).
DemoReplay ReplayDemoLog(const RobotModel& robot, const DemoLog& log,
                         const JointSpaceOptions& options = {});

}  // namespace graspsynth
