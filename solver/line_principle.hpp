#pragma once

/// @file
/// The line principle (the paper's first alternative to blending, which it did not build): a
/// grasp for any object orientation theta from models fitted over the whole library, inside and
/// outside its range. Weak entries (LinePrincipleOptions::min_score) are left out of every fit.
///
/// Models (object-centred table plane: world x, y axes, origin at the object centre):
/// - position: the wrist line fitted to the grasp positions (solver/wrist_line.hpp) and the
///   position along it, s(theta) = s0 + s1 theta (least squares over the entries); per side of
///   the handle when that side has two or more entries (see SideOrientationModel);
/// - height: the wrist above the object centre, linear in theta (per side, as the position);
/// - orientation, relative to the handle: the yaw of the hand's long axis z_H projected on the
///   table, measured from the handle direction, linear in theta and fitted per side of the
///   handle (bracket.hpp; a side switch turns this yaw by about 180 deg, which no smooth fit
///   over both sides could follow); the rest of the orientation (roll and pitch away from
///   "palm down, z_H horizontal", as a rotation vector in the hand frame) linear in theta per
///   side, held at its value at the side's first or last entry outside their range (a tilt
///   the operator never showed is not extrapolated);
/// - fingers: per joint, linear in theta, clamped to the range the entries span;
/// - approach: the mean of the entries' grasping motions expressed relative to their grasp pose
///   (positions in the grasp's yaw frame, rotations in the grasp's hand frame, finger offsets
///   from the grasp fingers), with the mean duration;
/// - the handle in the hand: the mean point of the handle's axis under the hand (where the
///   hand's forward axis z_H, seen from above, crosses it; the point nearest the wrist when the
///   hand lies along the handle), in the grasp's hand frame H (what the refinement's contact
///   constraint uses).

#include <string>
#include <vector>

#include "kinematics/hand_model.hpp"
#include "kinematics/scene_model.hpp"
#include "learning_data/grasp_library.hpp"
#include "solver/wrist_line.hpp"

namespace graspsynth {

/// Options of FitLinePrinciple.
struct LinePrincipleOptions {
  WristLineOptions line;  ///< the wrist-line fit
  int waypoints = 40;     ///< waypoints of the mean approach (and of generated motions), >= 2
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

/// The orientation model of one side of the handle.
struct SideOrientationModel {
  int side = 0;     ///< +1 or -1
  int entries = 0;  ///< entries of this side (0: the side was not demonstrated)
  LinearFit yaw;    ///< yaw of z_H from the handle direction, rad
  /// The roll and pitch left after the yaw: a rotation vector (rad) in the yawed, palm-down
  /// hand frame, each component linear in theta over [theta_lo, theta_hi] (this side's entries)
  /// and constant outside it.
  LinearFit residual[3];
  double theta_lo = 0.0, theta_hi = 0.0;  ///< rad

  /// The residual rotation vector at theta (rad).
  Eigen::Vector3d Residual(double theta) const;
  /// The position model of this side alone (a wrist line through this side's grasps, the
  /// position along it and the height), when the side has two or more entries with distinct
  /// grasp positions; otherwise the library-wide model is used. On a library whose grasps
  /// switch sides, the library-wide line crosses the handle and points between the sides.
  bool has_line = false;
  Line2d line;
  LinearFit s;
  LinearFit height;
};

/// One waypoint of the mean approach, relative to the grasp.
struct RelativeWaypoint {
  double u = 0.0;                               ///< normalized time, 0 (pre-grasp) .. 1 (grasp)
  Eigen::Vector3d p = Eigen::Vector3d::Zero();  ///< in the grasp's yaw frame, m
  Eigen::Vector3d r = Eigen::Vector3d::Zero();  ///< rotation vector in H of the grasp, rad
  HandVector df = HandVector::Zero();           ///< fingers minus the grasp's, rad
};

/// The fitted models.
struct LinePrincipleModel {
  bool valid = false;
  std::string message;  ///< why not valid
  WristLineResult wrist_line;
  LinearFit s;                    ///< position along wrist_line.line from its point, m
  LinearFit height;               ///< wrist z minus object centre z, m
  SideOrientationModel sides[2];  ///< [0]: side -1, [1]: side +1
  LinearFit fingers[kHandDof];
  HandVector finger_min = HandVector::Zero(), finger_max = HandVector::Zero();
  std::vector<RelativeWaypoint> approach;
  double duration = 1.0;                                     ///< s
  Eigen::Vector3d handle_in_hand = Eigen::Vector3d::Zero();  ///< m, frame H
  double theta_min = 0.0, theta_max = 0.0;                   ///< library range, rad
  std::vector<int> entry_sides;                              ///< side of each entry
  int fitted_entries = 0;  ///< entries the models were fitted over (the robust ones)

  /// The orientation model of `side` (+1 or -1).
  const SideOrientationModel& side_model(int side) const { return sides[side > 0 ? 1 : 0]; }
};

/// Fits the models over the library's entries. Needs at least two entries with distinct grasp
/// positions; otherwise the model is not valid (with the reason).
LinePrincipleModel FitLinePrinciple(const GraspLibrary& library, const SceneModel& scene,
                                    const LinePrincipleOptions& options = {});

/// The grasp wrist pose the models give at theta (rad) for `side` (+1 or -1; a side that was
/// not demonstrated uses the other side's yaw turned by 180 deg).
Eigen::Isometry3d LinePrincipleGraspPose(const LinePrincipleModel& model, const SceneModel& scene,
                                         double theta, int side);

/// The grasping motion the models give at theta (rad) for `side`: the mean approach placed at
/// LinePrincipleGraspPose, fingers from the finger models. Requires model.valid.
GraspingMotion LinePrincipleMotion(const LinePrincipleModel& model, const SceneModel& scene,
                                   double theta, int side);

}  // namespace graspsynth
