#pragma once

/// @file
/// The synthetic operator's options (learning_data/synthetic_operator.hpp) and their file format,
/// `graspsynth-operator/1` (JSON): the motion style, the variability, the hand's grips and the
/// per-orientation plans. Lengths in m, times in s; angles in rad here and in degrees in the
/// file (fields ending in `_deg`).

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "kinematics/types.hpp"

namespace graspsynth {

/// How the operator's hand takes the handle: a hook (learning_data/README.md). At the grasp
/// the handle's axis passes through the point (wrist_above_handle, 0, hook_reach) of the hand
/// frame H: `hook_reach` along the hand's long axis z_H and `wrist_above_handle` along the
/// palm normal x_H, which points down; with the hand level, the handle is that far ahead of
/// the wrist and that far below it. The hand pitches fingers-down by up to `max_pitch` so that it
/// crosses the handle squarely where the wrist is closer to the handle's line than the reach
/// (the rest of the difference is taken by turning the hand toward the handle's axis, as with
/// max_pitch = 0); it is then turned about the vertical by `yaw_offset` (positive turns the
/// fingertips toward the handle's free end, whichever side of the handle the wrist is on) and
/// rolled about z_H by `roll`. Lengths in m, angles in rad.
///
/// The hand closes from `open_hand` to `closed_hand` in the operator's close_duration, every
/// joint at once; with `thumb_close_duration` > 0 the four fingers close first (the thumb held
/// as opened) and the thumb closes after them, in that many seconds (scaled by the close's own
/// timing draw), so that the fingers hold the handle before the thumb, whose servo is four
/// times as strong (2 N m against 0.5), presses it: in MuJoCo's stiff servo mapping a thumb
/// that closes with the fingers pushes a light object out of the hand (experiments/grip_sweep.py).
struct GraspStyle {
  double hook_reach = 0.135;         ///< handle axis along z_H from the wrist, m
  double wrist_above_handle = 0.04;  ///< handle axis along x_H from the wrist, m
  double max_pitch = 0.0;            ///< largest fingers-down pitch, rad, in [0, pi/2)
  double yaw_offset = 0.0;           ///< rad
  double roll = 0.0;                 ///< rad, about z_H
  /// The thumb's closing after the fingers', s, >= 0; 0: the thumb closes with the fingers.
  double thumb_close_duration = 0.0;
  HandVector open_hand = DefaultOpenHook();
  HandVector closed_hand = DefaultClosedHook();

  /// Open hook: fingers straight and spread (index -20, ring and little +20 deg), the thumb
  /// laid along the index (thumb_j1 0, thumb_j2 40, thumb_j3 -10 deg), clear of the handle.
  static HandVector DefaultOpenHook();
  /// Closed hook: MCP 15 deg, PIP (= DIP) 85 deg for the four fingers (they stall on the
  /// handle and squeeze it against the proximal phalanges), the thumb as when open.
  static HandVector DefaultClosedHook();

  bool IsValid(std::string* why) const;
};

/// One way the operator grasps at an orientation: where the wrist should end up at the grasp,
/// and how the hand takes the handle there.
struct GraspStrategy {
  double weight = 1.0;     ///< relative frequency among the orientation's strategies, > 0
  double d = 0.35;         ///< intended horizontal wrist distance from the object centre, m
  double eta_deg = -60.0;  ///< intended polar angle of the wrist, deg from world +x
  /// The hand's grip for this strategy; empty takes OperatorOptions::grasp.
  std::optional<GraspStyle> grasp;
};

/// What the operator does at one object orientation.
struct OrientationPlan {
  double theta_deg = 60.0;          ///< object orientation, deg
  double pregrasp_eta_deg = -55.0;  ///< polar angle at which the reach enters the region, deg
  /// Trials at this orientation (a learning operator tries more where it fails more); 0 takes
  /// OperatorOptions::trials_per_orientation.
  int trials = 0;
  std::vector<GraspStrategy> strategies;
};

/// The operator model: motion style, variability and hand shapes. Lengths in m, angles in
/// rad, times in s.
struct OperatorOptions {
  uint64_t seed = 1;  ///< every trial is a function of (seed, position, theta, trial index)
  int trials_per_orientation = 10;  ///< >= 1; a plan's own `trials` overrides it
  double sample_rate_hz = 60.0;     ///< log rate (the paper's tracker: 30-60 Hz)
  std::vector<OrientationPlan> plans;
  /// Where the object stands in the trials: centres on the table (world, m), every plan made
  /// at each of them; empty: the scene's object centre only (the paper's fixed position). At
  /// another position the operator turns the plan's polar angles (the strategies' eta and the
  /// pre-grasp eta) by the change in the object's bearing from the robot base: he reaches for
  /// the handle from the robot's side, as at the scene's centre.
  std::vector<Eigen::Vector2d> positions;

  /// The hook of the strategies that have no grip of their own.
  GraspStyle grasp;

  // The path: rest -> outside the region -> inside -> above the grasp -> grasp -> lift.
  /// Rest wrist: rest_distance from the base in the direction of the object turned by
  /// rest_turn about the vertical (outside the grasp region), rest_height above the table.
  double rest_distance = 0.55;
  double rest_turn = -Radians(30.0);
  double rest_height = 0.30;
  double entry_out = 0.43;      ///< reach ends this far from the object centre (outside)
  double entry_in = 0.38;       ///< entry goes radially to this distance (inside)
  double travel_height = 0.16;  ///< entry height above the grasp wrist height
  double above_height = 0.06;   ///< the approach descends from this far above the grasp
  double lift_height = 0.12;    ///< wrist lift after the grasp button
  double reach_duration = 1.4;  ///< nominal durations of the sub-movements
  double entry_duration = 0.5;
  double approach_duration = 0.6;
  double descent_duration = 0.7;
  double close_duration = 0.7;
  double settle_duration = 0.25;
  double lift_duration = 1.0;
  double hold_duration = 1.2;
  double rest_duration = 0.3;

  // Variability, drawn per trial.
  double timing_spread = 0.12;         ///< every duration scaled by U[1 - s, 1 + s] (own draw)
  double position_noise = 0.005;       ///< std of the wrist's grasp position, per horizontal axis
  double height_noise = 0.003;         ///< std of the wrist's grasp height
  double yaw_noise = Radians(3.0);     ///< std of the hand's yaw at the grasp
  double path_noise = 0.02;            ///< std of the reach's mid-path bow, per axis
  double finger_noise = Radians(3.0);  ///< std of each closed-hand joint
  double sloppy_fraction = 0.15;       ///< share of trials made with sloppy_scale x the noise
  double sloppy_scale = 3.0;

  bool IsValid(std::string* why) const;
};

/// `format` of an operator file.
inline constexpr char kOperatorFormat[] = "graspsynth-operator/1";

/// Reads operator options (format graspsynth-operator/1, JSON). Fields that are absent keep
/// their defaults; `plans` is required, `positions` ([[x, y], ...], m) optional. A strategy's
/// optional `grasp` object holds the fields of its own grip (the GraspStyle fields of the top
/// level: hook_reach, wrist_above_handle, max_pitch_deg, yaw_offset_deg, roll_deg,
/// thumb_close_duration, open_hand_deg, closed_hand_deg); the ones it leaves out come from the top
/// level. Throws InputError naming the
/// file and the field.
OperatorOptions ReadOperatorOptions(const std::filesystem::path& path);
/// The same from the text of an operator file; `source` names it in messages.
OperatorOptions ParseOperatorOptions(std::string_view json_text, const std::string& source);
/// Writes them (atomically), every field included except a thumb_close_duration of 0 (the
/// default; files written before the field existed stay the same bytes).
void WriteOperatorOptions(const OperatorOptions& options, const std::filesystem::path& path);
/// Path of the shipped, calibrated operator of `object_name`: demos/operator.json in its
/// learning-data folder (learning_data/demos/operator.json for the pan;
/// ObjectLearningDataDirectory).
std::filesystem::path DefaultOperatorOptionsPath(const std::string& object_name = "pan");

}  // namespace graspsynth
