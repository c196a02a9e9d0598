#pragma once

/// @file
/// The line principle (the paper's first alternative to blending, which it did not build): a
/// grasp for any object orientation theta, inside and outside the library's range, with the
/// wrist on the operator's fitted wrist line. Weak entries (LinePrincipleOptions::min_score)
/// are left out of every fit.
///
/// Models (object-centred table plane: world x, y axes, origin at the object centre), per side
/// of the handle (bracket.hpp: a side switch turns the hand by about 180 deg and changes the
/// grip, which no model over both sides could follow):
/// - the wrist's position on the table: the wrist line fitted to the side's grasp positions
///   (analysis/wrist_line.hpp) and the position along it, s(theta) = s0 + s1 theta (least
///   squares over the entries); the library-wide line when the side has fewer than two
///   entries with distinct positions. This is the principle itself: the only model fitted.
/// - everything else is taken from the side's demonstrated grasps, relative to the handle,
///   linearly between the two that bracket theta and held at the first or last outside their
///   range (a grip the operator never showed is not extrapolated; see SideKnot): the wrist's
///   height above the object centre, the yaw of the hand's long axis z_H on the table measured
///   from the handle direction, the roll and pitch left after the yaw, the fingers at the
///   grasp, and the approach (the grasping motion relative to its grasp pose: positions in the
///   grasp's yaw frame, rotations in the grasp's hand frame, finger offsets from the grasp
///   fingers) with its duration;
/// - the handle in the hand: the mean point of the handle's axis under the hand (where the
///   hand's forward axis z_H, seen from above, crosses it; the point nearest the wrist when the
///   hand lies along the handle), in the grasp's hand frame H, over the whole library (what
///   the refinement's contact constraint uses).
///
/// So inside the range the line principle differs from the paper's blend only in where the
/// wrist goes: on the line instead of on the aslerp arc between the two demonstrations.

#include <string>
#include <vector>

#include "analysis/wrist_line.hpp"
#include "kinematics/hand_model.hpp"
#include "learning_data/grasp_library.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// Options of FitLinePrinciple.
struct LinePrincipleOptions {
  WristLineOptions line;         ///< the wrist-line fit
  int waypoints = 40;            ///< waypoints of every approach (and of generated motions), >= 2
  double side_dead_band = 0.01;  ///< m, as BracketOptions::side_dead_band
  /// Entries scoring below this (weak, as BracketOptions::min_score) are left out of the fits
  /// when two or more entries are not; [0, 1].
  double min_score = 0.5;

  bool IsValid(std::string* why) const;
};

/// A linear model y = a + b theta (theta in rad).
struct LinearFit {
  double a = 0.0;
  double b = 0.0;
  double operator()(double theta) const { return a + b * theta; }
};

/// One waypoint of an approach, relative to its grasp.
struct RelativeWaypoint {
  double u = 0.0;                               ///< normalized time, 0 (pre-grasp) .. 1 (grasp)
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< in the grasp's yaw frame, m
  Eigen::Vector3d r = Eigen::Vector3d::Zero();  ///< rotation vector in H of the grasp, rad
  HandVector df = HandVector::Zero();           ///< fingers minus the grasp's, rad
};

/// One demonstrated grasp of a side, relative to the handle.
struct SideKnot {
  double theta = 0.0;   ///< object orientation, rad
  double height = 0.0;  ///< wrist z minus object centre z at the grasp, m
  /// Yaw of z_H from the handle direction, rad, unwrapped about the side's nominal yaw (+-90
  /// deg: z_H across the handle).
  double yaw = 0.0;
  /// The roll and pitch left after the yaw: a rotation vector (rad) in the yawed, palm-down
  /// hand frame.
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
  HandVector fingers = HandVector::Zero();  ///< at the grasp, rad
  std::vector<RelativeWaypoint> approach;   ///< LinePrincipleOptions::waypoints of them
  double duration = 1.0;                    ///< s, pre-grasp to grasp
};

/// The models of one side of the handle.
struct SideModel {
  int side = 0;     ///< +1 or -1
  int entries = 0;  ///< fitted entries of this side (0: the side was not demonstrated)
  /// The position model of this side alone (a wrist line through this side's grasps and the
  /// position along it), when the side has two or more entries with distinct grasp positions;
  /// otherwise the library-wide model is used. On a library whose grasps switch sides, the
  /// library-wide line crosses the handle and points between the sides.
  bool has_line = false;
  Line2d line;
  LinearFit s;
  std::vector<SideKnot> knots;  ///< this side's entries, theta increasing

  /// The grasp relative to the handle at theta (rad): linear between the knots that bracket
  /// theta, the first or last knot outside them. Requires entries > 0.
  SideKnot At(double theta) const;
};

/// The fitted models.
struct LinePrincipleModel {
  bool valid = false;
  std::string message;  ///< why not valid
  WristLineResult wrist_line;
  LinearFit s;         ///< position along wrist_line.line from its point, m
  SideModel sides[2];  ///< [0]: side -1, [1]: side +1
  Eigen::Vector3d handle_in_hand = Eigen::Vector3d::Zero();  ///< m, frame H
  Eigen::Vector3d handle_along = Eigen::Vector3d::UnitX();   ///< the grip axis, object frame
  double theta_min = 0.0, theta_max = 0.0;                   ///< library range, rad
  std::vector<int> entry_sides;                              ///< side of each entry
  int fitted_entries = 0;  ///< entries the models were fitted over (the robust ones)

  /// The models of `side` (+1 or -1).
  const SideModel& side_model(int side) const { return sides[side > 0 ? 1 : 0]; }
};

/// The side of the handle (+1 or -1) of entry `e`'s grasp, relative to its own object (its
/// motion's object centre at its theta): HandleSide, and on the handle's line (within
/// dead_band, m) the sign of the hand's yaw relative to the handle.
int GraspSide(const SceneModel& scene, const LibraryEntry& e, double dead_band);

/// Fits the models over the library's entries (of one object position, theta increasing),
/// each grasp relative to its own object centre (its motion's object_position). Needs at least
/// two entries with distinct grasp positions; otherwise the model is not valid (with the
/// reason).
LinePrincipleModel FitLinePrinciple(const GraspLibrary& library, const SceneModel& scene,
                                    const LinePrincipleOptions& options = {});

/// The grasp wrist pose the models give at `placement` for `side` (+1 or -1; a side that was
/// not demonstrated uses the other side's grasps turned by 180 deg), the object at X_WO
/// (scene.ObjectPose(placement), computed once by the caller).
Eigen::Isometry3d LinePrincipleGraspPose(const LinePrincipleModel& model,
                                         const Placement& placement, const Eigen::Isometry3d& X_WO,
                                         int side);

/// The grasping motion the models give at `placement` for `side`, the object at X_WO
/// (scene.ObjectPose(placement)): the side's approach at the placement's theta placed at
/// LinePrincipleGraspPose, with the side's fingers at theta. Requires model.valid.
GraspingMotion LinePrincipleMotion(const LinePrincipleModel& model, const Placement& placement,
                                   const Eigen::Isometry3d& X_WO, int side);

}  // namespace graspsynth
