#include "simulation/trial_judge.hpp"
#include "common/demand.hpp"
#include "common/format.hpp"

#include <algorithm>
#include <cstdio>

namespace graspsynth {
namespace {

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
    case TrialOutcome::kTilted:
      return "tilted";
    case TrialOutcome::kCollision:
      return "collision";
    case TrialOutcome::kJointLimit:
      return "joint_limit";
    case TrialOutcome::kUnstable:
      return "unstable";
  }
  return "unknown";
}

bool TrialJudgeOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what, double v) {
    if (why) *why = std::string(what) + " = " + std::to_string(v);
    return false;
  };
  auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  if (!positive(lift_threshold)) return fail("lift_threshold (m)", lift_threshold);
  if (!(positive(lifted_min) && lifted_min <= lift_threshold)) {
    return fail("lifted_min (m, at most lift_threshold)", lifted_min);
  }
  if (!positive(knocked_tilt)) return fail("knocked_tilt (rad)", knocked_tilt);
  if (!positive(knocked_shift)) return fail("knocked_shift (m)", knocked_shift);
  if (!(positive(max_hold_tilt) && max_hold_tilt <= M_PI)) {
    return fail("max_hold_tilt (rad, in (0, pi])", max_hold_tilt);
  }
  if (!positive(max_speed)) return fail("max_speed (m/s)", max_speed);
  if (!positive(max_angular_speed)) return fail("max_angular_speed (rad/s)", max_angular_speed);
  if (!positive(max_kinetic_energy)) return fail("max_kinetic_energy (J)", max_kinetic_energy);
  return true;
}

TrialWatch StartTrialWatch(const Eigen::Isometry3d& X_WO_rest) {
  TrialWatch watch;
  watch.X_WO_rest = X_WO_rest;
  return watch;
}

void WatchStep(const JudgedWorld& data, const TrialJudgeOptions& options, TrialWatch* watch) {
  const ContactReport& c = data.contacts();
  const double time = data.time();
  const Eigen::Isometry3d X_WO = data.object_pose();
  const double lift = X_WO.translation().z() - watch->X_WO_rest.translation().z();
  watch->max_lift = std::max(watch->max_lift, lift);
  watch->max_penetration = std::max(watch->max_penetration, c.max_object_penetration);
  watch->max_tilt = std::max(watch->max_tilt, Tilt(X_WO));
  watch->max_shift = std::max(
      watch->max_shift, (X_WO.translation() - watch->X_WO_rest.translation()).head<2>().norm());
  if (c.object_table == 0 && lift >= options.lifted_min) {
    if (watch->airborne_since < 0.0) {
      watch->airborne_since = time;
      watch->X_HO_lifted = data.wrist_pose().inverse() * X_WO;
    }
    if (time - watch->airborne_since >= 0.1) watch->was_lifted = true;
  } else {
    watch->airborne_since = -1.0;
  }
}

bool AtRestForGood(const JudgedWorld& data, double t_motion) {
  const ContactReport& c = data.contacts();
  return data.time() > t_motion + 0.1 && c.object_table > 0 && c.object_hand == 0 &&
         c.object_arm == 0 && data.object_velocity().norm() < 1e-3 &&
         data.object_angular_velocity().norm() < 1e-2;
}

std::optional<TrialVerdict> EarlyVerdict(const JudgedWorld& data, const ArmModel& arm,
                                         const TrialJudgeOptions& options) {
  const double time = data.time();
  if (data.limit_violation() >= 0) {
    const int j = data.limit_violation();
    return TrialVerdict{TrialOutcome::kJointLimit,
                        arm.joint(j).name + " commanded to " +
                            Format("%.4f rad outside [%.4f, %.4f]", data.limit_violation_value(),
                                   arm.lower()[j], arm.upper()[j]) +
                            Format(" at t = %.3f s; the controller stops at the limit", time)};
  }
  const ContactReport& c = data.contacts();
  if (c.arm_table > 0) {
    return TrialVerdict{TrialOutcome::kCollision,
                        c.arm_table_link + Format(" hit the table at t = %.3f s", time)};
  }
  if (!data.IsFinite() || data.MaxDynamicSpeed() > options.max_speed ||
      data.MaxDynamicAngularSpeed() > options.max_angular_speed ||
      data.HandObjectKineticEnergy() > options.max_kinetic_energy) {
    return TrialVerdict{
        TrialOutcome::kUnstable,
        Format("numerical instability at t = %.3f s: speed %.3g m/s, angular speed %.3g rad/s",
               time, data.MaxDynamicSpeed(), data.MaxDynamicAngularSpeed())};
  }
  return std::nullopt;
}

TrialVerdict OdeFailureVerdict(double t, const char* what) {
  return {TrialOutcome::kUnstable, Format("numerical instability at t = %.3f s: ", t) + what};
}

TrialVerdict JudgeTrial(const JudgedWorld& data, const TrialWatch& watch, double held,
                        const TrialJudgeOptions& options) {
  const ContactReport& c = data.contacts();
  const double lift = data.object_pose().translation().z() - watch.X_WO_rest.translation().z();
  if (lift >= options.lift_threshold && c.object_hand > 0 && c.object_table == 0 &&
      c.object_arm == 0) {
    const double tilt = Tilt(data.object_pose());
    if (tilt > options.max_hold_tilt) {
      return {TrialOutcome::kTilted,
              Format("lifted %.1f mm and held %.2f s by the hand alone, but tilted %.1f deg "
                     "(limit %.1f deg)",
                     lift * 1e3, held, Degrees(tilt), Degrees(options.max_hold_tilt))};
    }
    return {TrialOutcome::kSuccess,
            Format("lifted %.1f mm and held %.2f s, touching only the hand", lift * 1e3, held)};
  }
  if (lift >= options.lift_threshold && c.object_arm > 0 && c.object_table == 0) {
    return {TrialOutcome::kTouchesOther,
            Format("the object is %.1f mm up but rests on the arm", lift * 1e3)};
  }
  if (watch.was_lifted || watch.max_lift >= options.lift_threshold) {
    std::string reason =
        Format("object slipped or dropped: lifted up to %.1f mm, %.1f mm at the end",
               watch.max_lift * 1e3, lift * 1e3);
    reason += c.object_table > 0 ? ", back on the table" : "";
    return {TrialOutcome::kDropped, reason};
  }
  if (watch.max_tilt > options.knocked_tilt || watch.max_shift > options.knocked_shift) {
    return {TrialOutcome::kKnockedOver,
            Format("object knocked over or pushed away: tilted up to %.1f deg, moved %.1f mm on "
                   "the table",
                   Degrees(watch.max_tilt), watch.max_shift * 1e3)};
  }
  return {TrialOutcome::kNotLifted,
          Format("object not lifted: its centre rose at most %.1f mm (needs %.0f mm)",
                 watch.max_lift * 1e3, options.lift_threshold * 1e3)};
}

int LoadShareGroup(const HandModel& hand, int hand_link) {
  if (hand_link < 0 || hand_link >= hand.joint_count()) return kLoadSharePalm;
  const std::string& name = hand.finger(hand.joint_finger(hand_link)).name;
  for (int k = 0; k < kLoadSharePalm; ++k) {
    if (kLoadShareGroups[static_cast<size_t>(k)] == name) return k;
  }
  return -1;
}

std::string HoldQuality::LoadBearers(double min_share) const {
  std::string text;
  for (size_t k = 0; k < load_share.size(); ++k) {
    if (load_share[k] < min_share || load_share[k] == 0.0) continue;
    if (!text.empty()) text += "+";
    text += std::string(kLoadShareGroups[k]);
  }
  return text.empty() ? "none" : text;
}

HoldQuality MeasureHold(const JudgedWorld& data, const TrialWatch& watch, const HandModel& hand) {
  HoldQuality q;
  const Eigen::Isometry3d X_WO = data.object_pose();
  q.end_tilt = Tilt(X_WO);
  q.max_tilt = watch.max_tilt;
  if (watch.airborne_since >= 0.0) {
    const Eigen::Isometry3d X_HO = data.wrist_pose().inverse() * X_WO;
    q.slip = (X_HO.translation() - watch.X_HO_lifted.translation()).norm();
    q.slip_angle =
        Eigen::AngleAxisd(watch.X_HO_lifted.linear().transpose() * X_HO.linear()).angle();
  }
  double total = 0.0;
  for (const HandObjectContact& c : data.hand_object_contacts()) {
    ++q.contacts;
    const int group = LoadShareGroup(hand, c.hand_link);
    GS_DEMAND(group >= 0, "a hand link outside the load share's groups");
    const double f = c.f_W.norm();
    q.load_share[static_cast<size_t>(group)] += f;
    total += f;
  }
  if (total > 0.0) {
    for (double& s : q.load_share) s /= total;
  }
  return q;
}

void StepTrialWorld(SimulationData* data, bool* free_space) {
  if (*free_space) {
    data->StepKinematically();
    const ContactReport& c = data->contacts();
    // anything touching ends free space; the contact is resolved from the next step on.
    if (c.object_hand + c.object_arm + c.finger_table > 0) *free_space = false;
  } else {
    data->Step();
  }
}

}  // namespace graspsynth
