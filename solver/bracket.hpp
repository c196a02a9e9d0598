#pragma once

/// @file
/// Bracket selection for the paper's blend (section IV-B): the two demonstrated orientations
/// theta1 < theta < theta2 nearest a query, and the test that tells whether their grasps can be
/// blended at all. Two grasps cannot be blended when the hand holds the object in two different
/// ways: the grasp orientations relative to the object differ by more than a threshold, or the
/// wrist is on different sides of the handle (reference/scene.md's hard case near 45 deg, where
/// the plain blend lays the hand along the handle).
///
/// Side of the handle: seen along the handle from the pan, +1 when the wrist is right of the
/// handle's line, -1 when left (ScriptedGraspOptions::side's convention), 0 when the wrist is
/// within BracketOptions::side_dead_band of the line.
///
/// A weak end: a representative whose robustness score in the library is below
/// BracketOptions::min_score (the most robust demonstration of its orientation still failed
/// most perturbed replays, e.g. the shipped 20 deg one: 0.20). A bracket with one weak end is
/// not blended either; the synthesis uses its robust end instead (synthesis.hpp). A query on a
/// weak entry's own orientation names the robust neighbour to use in its place.

#include <string>
#include <vector>

#include "learning_data/grasp_library.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// Options of SelectBracket.
struct BracketOptions {
  /// Two grasps whose wrist orientations relative to the object (R_OH) differ by more than
  /// this cannot be blended, rad.
  double max_orientation_change = Radians(60.0);
  /// A wrist closer than this to the handle's line has no side, m.
  double side_dead_band = 0.01;
  /// A query within this of a demonstrated orientation is that demonstration, deg.
  double exact_tolerance = 1e-6;
  /// A representative whose library score is below this is weak, [0, 1] (0: none is).
  double min_score = 0.5;

  bool IsValid(std::string* why) const;
};

/// Where a query falls among the library's orientations.
enum class BracketKind {
  kExact,       ///< on a demonstrated orientation: `lower` = `upper` is that entry
  kInside,      ///< strictly between entries `lower` and `upper`
  kBelowRange,  ///< below the first entry (`lower` = `upper` = 0)
  kAboveRange,  ///< above the last entry (`lower` = `upper` = the last)
  kEmpty,       ///< the library has no entry
};

/// "exact", "inside", "below_range", "above_range" or "empty".
const char* ToString(BracketKind kind);

/// The bracket of a query and whether its grasps can be blended.
struct Bracket {
  BracketKind kind = BracketKind::kEmpty;
  int lower = -1;  ///< entry index of theta1 (-1 when empty)
  int upper = -1;  ///< entry index of theta2
  double t = 0.0;  ///< blend parameter (theta - theta1) / (theta2 - theta1); 0 unless kInside
  /// Index of the entry nearest the query (ties: the lower one).
  int nearest = -1;
  /// Angle between the two grasp orientations relative to the object, rad (0 unless kInside).
  double orientation_change = 0.0;
  int side_lower = 0;  ///< side of the handle of the lower grasp (+1, -1, 0)
  int side_upper = 0;
  bool weak_lower = false;  ///< entry `lower` is weak (score < min_score); kExact: the entry
  bool weak_upper = false;  ///< entry `upper` is weak
  /// kExact on a weak entry: the nearer of its neighbours that is not weak (ties: the lower),
  /// to use in its place; -1 otherwise. `reason` then says why.
  int substitute = -1;
  /// False when the two grasps must not be blended (kInside only); `reason` says why.
  bool blendable = true;
  std::string reason;
};

/// The grasp wrist pose's side of the handle at object orientation theta (rad), see the file
/// comment.
int HandleSide(const SceneModel& scene, double theta, const Eigen::Vector3d& p_WH,
               double dead_band);
/// The same with the object at `placement`.
int HandleSide(const SceneModel& scene, const Placement& placement, const Eigen::Vector3d& p_WH,
               double dead_band);

/// The bracket of `theta_deg` in `library` (entries strictly increasing in theta).
Bracket SelectBracket(const GraspLibrary& library, const SceneModel& scene, double theta_deg,
                      const BracketOptions& options = {});

}  // namespace graspsynth
