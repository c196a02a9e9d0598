#include "simulation/trial.hpp"

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

std::string Format(const char* fmt, double a, double b = 0.0, double c = 0.0) {
  char buf[256];
  std::snprintf(buf, sizeof(buf), fmt, a, b, c);
  return buf;
}

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Angle between the object's up axis and the world's, rad.
double Tilt(const Eigen::Isometry3d& X_WO) {
  return std::acos(std::clamp(X_WO.linear()(2, 2), -1.0, 1.0));
}

}  // namespace

std::string_view ToString(TrialOutcome outcome) {
  switch (outcome) {
    case TrialOutcome::kSuccess:
      return "success";
    case TrialOutcome::kNotLifted:
      return "not_lifted";
    case TrialOutcome::kDropped:
      return "dropped";
    case TrialOutcome::kKnockedOver:
      return "knocked_over";
    case TrialOutcome::kTouchesOther:
      return "touches_other";
    case TrialOutcome::kCollision:
      return "collision";
    case TrialOutcome::kJointLimit:
      return "joint_limit";
    case TrialOutcome::kUnstable:
      return "unstable";
  }
  return "unknown";
}

bool TrialOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what, double v) {
    if (why) *why = std::string(what) + " = " + std::to_string(v);
    return false;
  };
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!(std::isfinite(time_step) && time_step >= 0.0 && time_step <= 0.02)) {
    return fail("time_step (s, 0 or up to 0.02)", time_step);
  }
  if (!(std::isfinite(hold) && hold >= 0.0)) return fail("hold (s)", hold);
  if (!positive(lift_threshold)) return fail("lift_threshold (m)", lift_threshold);
  if (!(positive(lifted_min) && lifted_min <= lift_threshold)) {
    return fail("lifted_min (m, at most lift_threshold)", lifted_min);
  }
  if (!positive(knocked_tilt)) return fail("knocked_tilt (rad)", knocked_tilt);
  if (!positive(knocked_shift)) return fail("knocked_shift (m)", knocked_shift);
  if (!positive(max_speed)) return fail("max_speed (m/s)", max_speed);
  if (!positive(max_angular_speed)) return fail("max_angular_speed (rad/s)", max_angular_speed);
  if (!positive(max_kinetic_energy)) return fail("max_kinetic_energy (J)", max_kinetic_energy);
  if (!(std::isfinite(proximity_margin) && proximity_margin >= 0.0 && proximity_margin < 0.5)) {
    return fail("proximity_margin (m)", proximity_margin);
  }
  if (!(std::isfinite(record_interval) && record_interval >= 0.0)) {
    return fail("record_interval (s)", record_interval);
  }
  return true;
}

double TrialOptions::step() const {
  if (time_step > 0.0) return time_step;
  return fidelity == Fidelity::kFast ? 0.004 : 0.001;
}

std::string TrialResult::BriefReport() const {
  std::ostringstream s;
  s << ToString(outcome) << ": " << reason << " (lift " << Format("%.4f", lift) << " m, "
    << statistics.dynamic_steps << " + " << statistics.kinematic_steps << " steps, "
    << Format("%.1f", cpu_time > 0 ? simulated_time / cpu_time : 0.0) << "x real time)";
  return s.str();
}

TrialResult RunTrial(const SimulationModel& model, const JointTrajectory& trajectory,
                     const TrialOptions& options, const StepObserver& observer) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid trial option: " + why);
  if (trajectory.samples.empty()) throw InputError("the trajectory has no samples");
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = ThreadCpuSeconds();
  const bool fast = options.fidelity == Fidelity::kFast;
  const double h = options.step();

  WorldOptions world_options;
  world_options.time_step = h;
  world_options.arm_mode = fast ? ArmMode::kKinematic : ArmMode::kDynamic;
  world_options.theta = trajectory.theta_deg * M_PI / 180.0;
  world_options.proximity_margin = options.proximity_margin;
  SimulationData data(model, world_options, trajectory.samples.front().arm,
                      trajectory.samples.front().hand);

  TrialResult result;
  result.counts = data.counts();
  const Eigen::Isometry3d X_WO_rest = model.scene().ObjectPose(world_options.theta);
  const double z_rest = X_WO_rest.translation().z();
  const double t_motion = trajectory.duration();
  result.planned_time = t_motion + options.hold;
  const long steps = std::lround(result.planned_time / h);

  bool kinematic = fast;
  double airborne_since = -1.0;  // time the object last left the table, or -1
  bool was_lifted = false;       // off the table, >= lifted_min up, for 0.1 s or more
  double max_tilt = 0.0, max_shift = 0.0;
  std::optional<TrialOutcome> decided;
  double next_record = 0.0;

  auto record = [&](double t) {
    if (options.record_interval <= 0.0 || t + 1e-9 < next_record) return;
    next_record += options.record_interval;
    result.states.push_back(
        {t, data.arm_positions(), data.hand_positions(), data.object_pose(), data.wrist_pose()});
  };
  record(0.0);

  for (long n = 0; n < steps && !decided; ++n) {
    const double t = n * h;
    const TrajectorySample now = SampleAt(trajectory, t);
    const TrajectorySample next = SampleAt(trajectory, t + h);
    data.SetArmCommand(ServoMode::kPosition, now.arm, (next.arm - now.arm) / h);
    data.SetHandCommand(ServoMode::kPosition, now.hand);

    try {
      if (kinematic && data.HandNearObject()) kinematic = false;
      if (kinematic) {
        data.StepKinematically();
        const ContactReport& c = data.contacts();
        // anything touching ends free space; the contact is resolved from the next step on.
        if (c.object_hand + c.object_arm + c.finger_table > 0) kinematic = false;
      } else {
        data.Step();
      }
    } catch (const OdeError& e) {
      decided = TrialOutcome::kUnstable;
      result.reason = Format("numerical instability at t = %.3f s: ", data.time()) + e.what();
      break;
    }
    const double time = data.time();
    if (observer) observer(data);

    const ContactReport& c = data.contacts();
    if (data.limit_violation() >= 0) {
      const int j = data.limit_violation();
      const ArmModel& arm = model.robot().arm;
      decided = TrialOutcome::kJointLimit;
      result.reason = arm.joint(j).name + " commanded to " +
                      Format("%.4f rad outside [%.4f, %.4f]", data.limit_violation_value(),
                             arm.lower()[j], arm.upper()[j]) +
                      Format(" at t = %.3f s; the controller stops at the limit", time);
      break;
    }
    if (c.arm_table > 0) {
      decided = TrialOutcome::kCollision;
      result.reason = c.arm_table_link + Format(" hit the table at t = %.3f s", time);
      break;
    }
    if (!data.IsFinite() || data.MaxDynamicSpeed() > options.max_speed ||
        data.MaxDynamicAngularSpeed() > options.max_angular_speed ||
        data.HandObjectKineticEnergy() > options.max_kinetic_energy) {
      decided = TrialOutcome::kUnstable;
      result.reason =
          Format("numerical instability at t = %.3f s: speed %.3g m/s, angular speed %.3g rad/s",
                 time, data.MaxDynamicSpeed(), data.MaxDynamicAngularSpeed());
      break;
    }

    const Eigen::Isometry3d X_WO = data.object_pose();
    const double lift = X_WO.translation().z() - z_rest;
    result.max_lift = std::max(result.max_lift, lift);
    result.max_penetration = std::max(result.max_penetration, c.max_object_penetration);
    max_tilt = std::max(max_tilt, Tilt(X_WO));
    max_shift =
        std::max(max_shift, (X_WO.translation() - X_WO_rest.translation()).head<2>().norm());
    if (c.object_table == 0 && lift >= options.lifted_min) {
      if (airborne_since < 0.0) airborne_since = time;
      if (time - airborne_since >= 0.1) was_lifted = true;
    } else {
      airborne_since = -1.0;
    }
    record(time);

    // fast path: once the robot holds still and the object lies on the table untouched,
    // nothing can change any more.
    if (fast && time > t_motion + 0.1 && c.object_table > 0 && c.object_hand == 0 &&
        c.object_arm == 0 && data.object_velocity().norm() < 1e-3 &&
        data.object_angular_velocity().norm() < 1e-2) {
      break;
    }
  }

  result.simulated_time = data.time();
  result.final_object_pose = data.object_pose();
  result.lift = result.final_object_pose.translation().z() - z_rest;
  result.statistics = data.statistics();
  if (decided) {
    result.outcome = *decided;
  } else {
    const ContactReport& c = data.contacts();
    const double lift = result.lift;
    const double held = result.simulated_time - t_motion;
    if (lift >= options.lift_threshold && c.object_hand > 0 && c.object_table == 0 &&
        c.object_arm == 0) {
      result.outcome = TrialOutcome::kSuccess;
      result.reason =
          Format("lifted %.1f mm and held %.2f s, touching only the hand", lift * 1e3, held);
    } else if (lift >= options.lift_threshold && c.object_arm > 0 && c.object_table == 0) {
      result.outcome = TrialOutcome::kTouchesOther;
      result.reason = Format("the object is %.1f mm up but rests on the arm", lift * 1e3);
    } else if (was_lifted || result.max_lift >= options.lift_threshold) {
      result.outcome = TrialOutcome::kDropped;
      result.reason = Format("object slipped or dropped: lifted up to %.1f mm, %.1f mm at the end",
                             result.max_lift * 1e3, lift * 1e3);
      result.reason += c.object_table > 0 ? ", back on the table" : "";
    } else if (max_tilt > options.knocked_tilt || max_shift > options.knocked_shift) {
      result.outcome = TrialOutcome::kKnockedOver;
      result.reason = Format(
          "object knocked over or pushed away: tilted up to %.1f deg, moved %.1f mm on the table",
          max_tilt * 180.0 / M_PI, max_shift * 1e3);
    } else {
      result.outcome = TrialOutcome::kNotLifted;
      result.reason = Format("object not lifted: its centre rose at most %.1f mm (needs %.0f mm)",
                             result.max_lift * 1e3, options.lift_threshold * 1e3);
    }
  }
  result.wall_time =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.cpu_time = ThreadCpuSeconds() - cpu_start;
  return result;
}

}  // namespace graspsynth
