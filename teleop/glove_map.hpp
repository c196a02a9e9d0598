#pragma once

/// @file
/// From the 14 sensors of a 5DT Data Glove 14 Ultra (values in [0, 1] after the glove's own
/// open/closed calibration) to the 16 actuated joints of the Gifu Hand III, after the scheme of
/// reference/robot.md 3.2: 14 joints follow one sensor each through a linear map, and two are
/// derived - the thumb's opposition (thumb_j1) from the thumb's spread and flexion, and the
/// middle finger's ab/adduction (middle_j1), the reference finger, held at a fixed value.

#include <array>

#include "kinematics/hand_model.hpp"

namespace graspsynth::teleop {

/// 5DT sensor indices (SDK order).
enum GloveSensor : int {
  kThumbNear = 0,
  kThumbFar,
  kThumbIndex,
  kIndexNear,
  kIndexFar,
  kIndexMiddle,
  kMiddleNear,
  kMiddleFar,
  kMiddleRing,
  kRingNear,
  kRingFar,
  kRingLittle,
  kLittleNear,
  kLittleFar
};

/// One joint's map: q = at_zero + (at_one - at_zero) * g for the sensor value g.
struct GloveJointMap {
  int sensor = -1;       ///< GloveSensor, or -1 for a derived joint
  double at_zero = 0.0;  ///< rad, joint value at g = 0
  double at_one = 0.0;   ///< rad, joint value at g = 1
};

/// The map of all 16 joints (index = f0..f15).
struct GloveMap {
  std::array<GloveJointMap, kHandDof> joints;

  /// The default map for a hand: flexion sensors span each joint's range from 0 (open) to its
  /// upper limit (closed); abduction sensors spread the fingers by up to 15 deg; thumb_j2 spans
  /// its range. The derived joints: thumb_j1 rises with the mean of (1 - thumb-index spread)
  /// and thumb flexion over its range; middle_j1 stays at 0.
  static GloveMap Default(const HandModel& hand);
};

/// Joint values f0..f15 (rad, clamped to the hand's limits) for glove values g (14 values,
/// each clamped to [0, 1]).
HandVector GloveToJoints(const GloveMap& map, const HandModel& hand,
                         const Eigen::Ref<const Eigen::Matrix<double, 14, 1>>& g);

}  // namespace graspsynth::teleop
