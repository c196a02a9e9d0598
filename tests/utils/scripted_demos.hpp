#pragma once

/// @file
/// Demonstration logs made from the scripted grasp (motion/scripted_grasp.hpp), for the
/// tests of the representative selection and `graspsynth select`: the joint trajectory of
/// BuildScriptedGrasp, sampled at 60 Hz, turned into the wrist pose (arm FK * X_FH) and
/// fingers of a v1 log, with the object positions of a real (kFast) RunTrial of the same
/// trajectory, so the success label is what the physics did.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "kinematics/pose_math.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/scripted_grasp.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial.hpp"

namespace graspsynth::testing {

/// The log of the scripted grasp `grasp` (its theta_deg is the log's), named `file`: samples
/// every 1/60 s from 0 to the end of the trajectory, the grasp event at the first sample after
/// the hand has closed (the scripted trajectory's 4th waypoint), the end event on the last
/// sample; the object centre from a recorded RunTrial. Fails the test (and returns an empty
/// log) when the scripted grasp cannot be built.
inline DemoLog ScriptedDemoLog(const SimulationModel& model, const ScriptedGraspOptions& grasp,
                               const std::string& file) {
  DemoLog log;
  const RobotModel& robot = model.robot();
  const ScriptedGraspResult scripted = BuildScriptedGrasp(robot, model.scene(), grasp);
  EXPECT_TRUE(scripted.ok) << scripted.message;
  if (!scripted.ok) return log;
  const JointTrajectory& trajectory = scripted.trajectory;

  const double dt = 1.0 / 60.0;
  TrialOptions trial;
  trial.record_interval = dt;
  const TrialResult result = RunTrial(model, trajectory, trial);
  EXPECT_FALSE(result.states.empty());

  log.source = file;
  log.metadata.theta_deg = grasp.theta_deg;
  log.metadata.object_position =
      model.scene().ObjectPose(grasp.theta_deg * M_PI / 180.0).translation();
  log.metadata.trial = std::filesystem::path(file).stem().string();
  log.metadata.operator_name = "scripted";
  log.metadata.sample_rate_hz = 60.0;

  const double t_closed = trajectory.waypoints.at(3).t;
  const int n = static_cast<int>(std::floor(trajectory.duration() / dt + 1e-9)) + 1;
  size_t state = 0;
  bool grasp_marked = false;
  for (int k = 0; k < n; ++k) {
    const double t = k * dt;
    const TrajectorySample command = SampleAt(trajectory, t);
    const Eigen::Isometry3d X_WH = ArmFlangePose(robot.arm, command.arm) * robot.X_FH;
    DemoSample s;
    s.t = t;
    s.p_WH = X_WH.translation();
    s.q_WH = Canonical(Eigen::Quaterniond(X_WH.linear()));
    s.f = command.hand;
    // the last recorded state at or before t (a trial stopped early keeps its last state).
    while (state + 1 < result.states.size() && result.states[state + 1].t <= t + 1e-9) ++state;
    s.p_WO = result.states.empty() ? log.metadata.object_position
                                   : Eigen::Vector3d(result.states[state].X_WO.translation());
    if (!grasp_marked && t > t_closed) {
      s.event = DemoEvent::kGrasp;
      grasp_marked = true;
    }
    log.samples.push_back(s);
  }
  log.samples.back().event = DemoEvent::kEnd;
  return log;
}

/// The scripted grasp's log for `theta_deg` with the default shape.
inline DemoLog ScriptedDemoLog(const SimulationModel& model, double theta_deg,
                               const std::string& file) {
  ScriptedGraspOptions grasp;
  grasp.theta_deg = theta_deg;
  return ScriptedDemoLog(model, grasp, file);
}

}  // namespace graspsynth::testing
