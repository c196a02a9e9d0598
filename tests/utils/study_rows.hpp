#pragma once

// A synthesis table's row with every field away from its default (the study's tests of its
// codec and of its field list).

#include "studies/study.hpp"

namespace graspsynth::testing {

// A row with every field away from its default.
inline StudyRow FullRow() {
  StudyRow row;
  row.theta_deg = 65.0;
  row.at = Eigen::Vector2d(-0.27, 0.87 + 1e-17);
  row.method = "interp+refine";
  row.message = "ok, with words";
  row.used = SynthesisMethod::kNearest;
  row.fallback = true;
  row.fallback_reason.kind = FallbackKind::kTurnedDemo;
  row.fallback_reason.bracket_reason = "the blend dropped the pan";
  row.fallback_reason.lower_deg = 60.0;
  row.fallback_reason.upper_deg = 70.0;
  row.fallback_reason.used_deg = 60.0;
  row.fallback_reason.robust = true;
  row.fallback_reason.min_psi_width = 0.17;
  row.fallback_reason.line_unreachable = true;
  row.fallback_reason.side = -1;
  row.fallback_reason.blend_failed = true;
  row.fallback_reason.cell = "cell of 4";
  row.fallback_reason.used_placement = "(-0.25, 0.85, 60 deg)";
  row.refined = true;
  row.gate_run = true;
  row.status = SynthesisStatus::kOk;
  row.nominal_success = true;
  row.nominal_outcome = TrialOutcome::kTilted;
  row.nominal_reason = "held tilted";
  row.trials = 10;
  row.successes = 9;
  row.robustness = 0.9;
  row.ci_low = 0.5958499739;
  row.ci_high = 0.9821237;
  row.passed = true;
  row.gate_reason = "passed";
  row.epsilon = 0.0123;
  row.force_closure = true;
  row.failures = "dropped 1";
  row.nominal_hold.end_tilt = 0.01;
  row.nominal_hold.max_tilt = 0.2;
  row.nominal_hold.slip = 0.003;
  row.nominal_hold.slip_angle = 0.04;
  row.nominal_hold.contacts = 7;
  row.nominal_hold.load_share = {0.5, 0.2, 0.1, 0.1, 0.05, 0.05};
  row.hold_margin.measured = true;
  row.hold_margin.slip_mm = 3.0;
  row.hold_margin.slip_deg = 2.3;
  row.hold_margin.end_tilt_deg = 0.6;
  row.hold_margin.contacts = {1, 2, 0, 1, 0, 3};
  row.hold_margin.load_share = {0.5, 0.2, 0.1, 0.1, 0.05, 0.05};
  row.hold_margin.load_bearing_links = 4;
  row.hold_margin.fingertips_only = true;
  row.hold_margin.epsilon_weight = 0.21;
  row.hold_margin.torque_scale_m = 0.09;
  row.hold_margin.friction_use_max = 1.3;
  row.hold_margin.friction_use_mean = 0.6;
  row.hold_margin.normal_force_weight = 30.5;
  row.hold_margin_shortfall = "friction use 1.30 > 0.95";
  SensitivityResult s;
  s.trials_per_cell = 2;
  SensitivityRow sr;
  sr.factor = PhysicsFactor::kStep;
  sr.low.physics.variation.object_com_offset = Eigen::Vector3d(0.01, -0.02, 0.0);
  sr.low.trials = 2;
  sr.low.successes = 1;
  sr.low.failures = "dropped 1";
  sr.high.physics.time_step = 0.001;
  sr.high.physics.variation.hand_effort = 0.8;
  sr.high.trials = 2;
  sr.high.successes = 2;
  s.rows = {sr, sr};
  s.wall_time = 3.5;
  row.sensitivity = s;
  MujocoSweepSummary mujoco;
  mujoco.runs = 16;
  mujoco.successes = 15;
  mujoco.success_fraction = 0.9375;
  mujoco.slip_median = 0.002;
  mujoco.slip_worst = 0.031;
  mujoco.slip_angle_median = 0.01;
  mujoco.slip_angle_worst = 0.2;
  mujoco.failing = "pyramidal/soft";
  row.mujoco = mujoco;
  row.seed = 0xFEDCBA9876543210ULL;
  row.synthesis_s = 1.25;
  row.gate_s = 4.5;
  row.source_thetas_deg = {60.0, 70.0};
  return row;
}

}  // namespace graspsynth::testing
