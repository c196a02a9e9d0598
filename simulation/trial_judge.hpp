#pragma once

/// @file
/// The judgement of a grasp-and-lift trial, shared by the offline trials (simulation/trial.hpp)
/// and the live teleoperation session (teleop/teleop_session.hpp), and the physics step both
/// take. DESIGN.md defines success: after the lift and a hold, the object's centre is at least
/// lift_threshold above its resting height and the object touches only the hand.
///
/// A trial is watched step by step:
/// 1. after each step, EarlyVerdict decides what ends a trial at once: an arm command outside
///    the joint limits, the arm or the palm on the table, a numerical instability;
/// 2. otherwise WatchStep updates the figures the judgement needs (TrialWatch: lift, highest
///    lift, time off the table, tilt, shift on the table, deepest penetration);
/// 3. at the end, JudgeTrial turns the world's last contacts and the watch into the outcome,
///    and MeasureHold describes how the object sits in the hand (HoldQuality).

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include "kinematics/arm_model.hpp"
#include "kinematics/hand_model.hpp"
#include "simulation/simulation_data.hpp"

namespace graspsynth {

/// How a trial ended.
enum class TrialOutcome {
  kSuccess,       ///< lifted >= lift_threshold, held, touching only the hand
  kNotLifted,     ///< the object never left the table (no grasp)
  kDropped,       ///< the object had been lifted, then slipped or dropped
  kKnockedOver,   ///< the object was knocked over or pushed away without being lifted
  kTouchesOther,  ///< lifted, but resting on something other than the hand (the arm)
  kTilted,        ///< lifted and held by the hand alone, but hanging tilted beyond the limit
  kCollision,     ///< the arm, the hand mount or the palm hit the table
  kJointLimit,    ///< an arm command outside the joint limits (the controller stops there)
  kUnstable,      ///< numerical instability: non-finite state or runaway energy
};

/// Lowercase name of an outcome, e.g. "not_lifted" (report files use it).
std::string_view ToString(TrialOutcome outcome);

/// The thresholds of the judgement.
struct TrialJudgeOptions {
  /// Success needs the object centre this far above its resting height at the end, m.
  double lift_threshold = 0.05;
  /// Below this lift the object counts as not lifted (for the failure reason), m.
  double lifted_min = 0.01;
  /// Object tilt (rad) or horizontal shift (m) beyond which an object that was not lifted
  /// counts as knocked over or pushed away.
  double knocked_tilt = Radians(20.0);
  double knocked_shift = 0.03;
  /// A held object may be tilted at most this much at the end of the hold, rad (the angle of
  /// its up axis from vertical); beyond it the trial is kTilted. 30 deg: the demonstrations
  /// lift the pan level (a few degrees), a pan at 30 deg still keeps what lies in it and its
  /// load still acts mostly along the fingers' grip, while one hanging at 60 deg from a
  /// sideways pinch is held by friction at its limit (docs/architecture.md, "Robustness under the
  /// contact model").
  double max_hold_tilt = Radians(30.0);
  /// Instability: a finger or the object faster than this (m/s, rad/s) or with more kinetic
  /// energy (J; the hand moves at well under 1 m/s) is a numerical failure.
  double max_speed = 5.0;
  double max_angular_speed = 200.0;
  double max_kinetic_energy = 2.0;

  /// True when every value is finite and in range; otherwise false with the reason.
  bool IsValid(std::string* why) const;
};

/// An outcome and the sentence, with the figures, that decided it.
struct TrialVerdict {
  TrialOutcome outcome = TrialOutcome::kUnstable;
  std::string reason;
};

/// The figures of a trial that its judgement needs, updated after every step by WatchStep.
struct TrialWatch {
  Eigen::Isometry3d X_WO_rest = Eigen::Isometry3d::Identity();  ///< object pose at rest
  double max_lift = 0.0;         ///< highest the object centre got above its rest height, m
  double max_penetration = 0.0;  ///< deepest contact involving the object, m
  double max_tilt = 0.0;         ///< largest angle of the object's up axis from vertical, rad
  double max_shift = 0.0;        ///< largest horizontal distance from its rest position, m
  double airborne_since = -1.0;  ///< time (s) the object last left the table, or -1
  bool was_lifted = false;       ///< off the table, >= lifted_min up, for 0.1 s or more
  /// The object's pose in the hand-mount frame H when it last left the table (valid while
  /// airborne_since >= 0): where slip is measured from.
  Eigen::Isometry3d X_HO_lifted = Eigen::Isometry3d::Identity();
};

/// The groups of HoldQuality::load_share, in order: five fingers by name, then the palm (and
/// hand mount). For now a hand's fingers must bear some of these names (SimulationModel checks
/// it; the Gifu's are all five): a finger's contacts count toward the group of its name, and a
/// group the hand has no finger for stays 0. The file formats keep these six keys until the load
/// share is sized by the hand (docs/robot-file-draft.md, step 3).
inline constexpr std::array<std::string_view, 6> kLoadShareGroups = {"thumb", "index",  "middle",
                                                                     "ring",  "little", "palm"};
/// The index of the palm's group in kLoadShareGroups.
inline constexpr int kLoadSharePalm = 5;

/// The group in kLoadShareGroups of hand link `hand_link` (a HandJointVector index, or the
/// hand's joint count for the palm and mount) of `hand`; -1 for a finger whose name is not a
/// group's.
int LoadShareGroup(const HandModel& hand, int hand_link);

/// How the object sits in the hand at the end of a trial (reported for every trial).
struct HoldQuality {
  double end_tilt = 0.0;  ///< angle of the object's up axis from vertical at the end, rad
  double max_tilt = 0.0;  ///< the largest such angle during the trial, rad
  /// Motion of the object relative to the hand from when it last left the table to the end:
  /// its frame's displacement (m) and rotation (rad) in the hand-mount frame; 0 when it is
  /// not off the table at the end.
  double slip = 0.0;
  double slip_angle = 0.0;
  int contacts = 0;  ///< object-hand contact points at the end
  /// Share of the object-hand contact force at the end carried by each group of
  /// kLoadShareGroups (fingers by name, then the palm), summing to 1; all 0 without contact
  /// force.
  std::array<double, kLoadShareGroups.size()> load_share{};

  /// The fingers (and "palm") that carry at least `min_share` of the load, e.g.
  /// "thumb+index"; "none" without load.
  std::string LoadBearers(double min_share = 0.1) const;
};

/// A watch of a trial whose object rests at X_WO_rest.
TrialWatch StartTrialWatch(const Eigen::Isometry3d& X_WO_rest);

/// Updates `watch` from the world after a step.
void WatchStep(const JudgedWorld& data, const TrialJudgeOptions& options, TrialWatch* watch);

/// What ends a trial at once after a step, checked in this order: an arm joint commanded
/// beyond its limit (`arm` names it), an arm link or the palm on the table, a non-finite state
/// or a finger or the object faster or more energetic than the options allow. std::nullopt when
/// the trial goes on.
std::optional<TrialVerdict> EarlyVerdict(const JudgedWorld& data, const ArmModel& arm,
                                         const TrialJudgeOptions& options);

/// True once the trial's motion (`t_motion`, s) is over by 0.1 s and the object lies on the
/// table untouched and still: nothing can change any more, so a trial may stop there.
bool AtRestForGood(const JudgedWorld& data, double t_motion);

/// The verdict of an ODE failure (`what`) at simulated time `t` (s).
TrialVerdict OdeFailureVerdict(double t, const char* what);

/// Judges a trial at its end from the world's last contacts and object pose and the watch;
/// `held` (s) is how long the last command was held (for the reason). In this order: success,
/// resting on the arm (touches_other), dropped, knocked over, not lifted.
TrialVerdict JudgeTrial(const JudgedWorld& data, const TrialWatch& watch, double held,
                        const TrialJudgeOptions& options);

/// How the object sits in the hand at the end of a trial: the world's object pose and last
/// object-hand contacts (with their forces, their links numbered as in `hand`) and the watch.
HoldQuality MeasureHold(const JudgedWorld& data, const TrialWatch& watch, const HandModel& hand);

/// One physics step of a trial whose arm follows its controller kinematically: while
/// `*free_space`, a kinematic step without contact detail (SimulationData::StepKinematically),
/// until anything touches; from then on (`*free_space` turns false) full steps. Throws what the
/// steps throw (OdeError).
void StepTrialWorld(SimulationData* data, bool* free_space);

}  // namespace graspsynth
