#pragma once

/// @file
/// Shared inputs of the teleoperation tests: a synthetic demonstration made from the scripted
/// grasp (motion/scripted_grasp.hpp), as an operator would have recorded it, and commands
/// for the robot's wrist.

#include <gtest/gtest.h>

#include <cmath>

#include "kinematics/arm_model.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/scripted_grasp.hpp"
#include "simulation/trial.hpp"
#include "teleop/protocol.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth::testing {

/// The scripted grasp for theta_deg as a v1 log at rate_hz: the wrist pose X_WH = FK(arm) X_FH
/// and the fingers of the trajectory at every sample time, the grasp event at the sample
/// nearest the trajectory's grasp waypoint, the end event on the last sample (the end of the
/// trajectory), the object centre where the nominal trial (simulation/trial.hpp) had it.
/// `trial` (if given) receives that nominal trial's result.
inline DemoLog ScriptedDemoLog(double theta_deg, double rate_hz, TrialResult* trial = nullptr) {
  const SimulationModel& model = ShippedSimulationModel();
  const RobotModel& robot = model.robot();
  ScriptedGraspOptions options;
  options.theta_deg = theta_deg;
  const ScriptedGraspResult grasp = BuildScriptedGrasp(robot, model.scene(), options);
  EXPECT_TRUE(grasp.ok) << grasp.message;
  TrialOptions trial_options;
  trial_options.record_interval = 1.0 / rate_hz;
  const TrialResult nominal = RunTrial(model, grasp.trajectory, trial_options);
  if (trial) *trial = nominal;

  DemoLog log;
  log.source = "scripted grasp";
  log.metadata.theta_deg = theta_deg;
  log.metadata.object_position = model.scene().ObjectPose(theta_deg * M_PI / 180.0).translation();
  log.metadata.sample_rate_hz = rate_hz;
  const double t_grasp = grasp.trajectory.waypoints.at(2).t;
  const int n = static_cast<int>(std::floor(grasp.trajectory.duration() * rate_hz + 1e-9));
  const int k_grasp = static_cast<int>(std::lround(t_grasp * rate_hz));
  for (int k = 0; k <= n; ++k) {
    const double t = k / rate_hz;
    const TrajectorySample s = SampleAt(grasp.trajectory, t);
    const Eigen::Isometry3d X_WH = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
    DemoSample d;
    d.t = t;
    d.p_WH = X_WH.translation();
    d.q_WH = Eigen::Quaterniond(X_WH.linear());
    d.f = s.hand;
    d.event = k == k_grasp ? DemoEvent::kGrasp : k == n ? DemoEvent::kEnd : DemoEvent::kNone;
    d.p_WO = log.metadata.object_position;
    double best = 1e9;
    for (const TrialState& state : nominal.states) {
      if (std::abs(state.t - t) < best) {
        best = std::abs(state.t - t);
        d.p_WO = state.X_WO.translation();
      }
    }
    log.samples.push_back(d);
  }
  return log;
}

/// An operator command in joint mode: sensor pose X_TS, fingers f, buttons.
inline teleop::OperatorCommand JointCommand(uint32_t sequence, const Eigen::Isometry3d& X_TS,
                                            const HandVector& f, uint8_t buttons = 0) {
  teleop::OperatorCommand c;
  c.sequence = sequence;
  c.sender_time = sequence / 60.0;
  c.p_TW = X_TS.translation();
  c.q_TW = Eigen::Quaterniond(X_TS.linear()).normalized();
  c.hand_mode = teleop::HandMode::kJoints;
  c.buttons = buttons;
  c.fingers = f;
  return c;
}

}  // namespace graspsynth::testing
