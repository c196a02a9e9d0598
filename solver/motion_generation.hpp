#pragma once

/// @file
/// Stage 1 of the synthesis (synthesis.hpp): the grasping motion for a task, by one of three
/// methods, with the fallback policy of the interp method.
///
/// Methods:
/// - interp: the paper's blend (motion/interpolation.hpp) of the bracket theta1 < theta <
///   theta2 (bracket.hpp); a demonstrated theta is that demonstration, unless it is weak
///   (bracket.hpp) and a neighbour is not: then that neighbour turned with the object. Outside
///   the library's range: an error (kOutOfRange) that names the range. A bracket that cannot be
///   blended (the hard case, or one weak end) falls back, in this order: (1) the nearer
///   demonstration of the bracket (the robust one when one end is weak) turned with the object
///   about its vertical axis (the hand keeps the demonstrated hold of the handle; accepted when
///   its grasp and pre-grasp are reachable on the start branch with min_psi_width to spare);
///   (2) the line principle on that demonstration's side of the handle; (3) the plain blend,
///   left to the refinement. The result says which and why (FallbackReason). A blendable
///   bracket whose blend failed its nominal trial in physics (MotionGenerationOptions::
///   reject_blend, set by SynthesizeAndValidate) takes the same fallbacks.
/// - nearest: the nearest demonstration turned with the object (any theta).
/// - line: the line principle (line_principle.hpp) on the nearest demonstration's side (any
///   theta).

#include <string>
#include <vector>

#include "kinematics/arm_ik.hpp"
#include "motion/interpolation.hpp"
#include "solver/bracket.hpp"
#include "solver/synthesis_model.hpp"

namespace graspsynth {

/// How the grasping motion is made.
enum class SynthesisMethod { kInterp, kLine, kNearest };

/// "interp", "line" or "nearest".
const char* ToString(SynthesisMethod method);
/// Parses "interp", "line" or "nearest"; throws InputError naming the value otherwise.
SynthesisMethod ParseSynthesisMethod(const std::string& text);

/// A demonstration the grasp was made from.
struct SourceDemo {
  int entry = -1;  ///< library entry index
  double theta_deg = 0.0;
  std::string file;
  std::string trial;
  double weight = 0.0;  ///< its share in the grasp (blend weights sum to 1)
};

/// What the interp method fell back to.
enum class FallbackKind {
  kNone,             ///< no fallback: the requested method was used
  kRobustNeighbour,  ///< a weak demonstrated theta: its robust neighbour turned with the object
  kTurnedDemo,       ///< unblendable bracket: the nearer (or robust) end turned with the object
  kLinePrinciple,    ///< unblendable bracket, the turned end unreachable: the line principle
  kPlainBlend,       ///< unblendable bracket, nothing else reachable: the plain blend
  kPartialBlend,     ///< unblendable cell: the blend of its vertices that can be blended
};

/// "none", "robust_neighbour", "turned_demo", "line_principle", "plain_blend" or
/// "partial_blend".
const char* ToString(FallbackKind kind);

/// Why a method other than the requested one was used, and the figures of what was tried.
struct FallbackReason {
  FallbackKind kind = FallbackKind::kNone;
  std::string bracket_reason;  ///< Bracket::reason: why the bracket cannot be used as it is
  double lower_deg = 0.0;      ///< the bracket's ends, deg (not kRobustNeighbour)
  double upper_deg = 0.0;
  double used_deg = 0.0;          ///< the demonstration turned with the object, deg
  bool robust = false;            ///< kTurnedDemo: exactly one end was weak (the robust one used)
  double min_psi_width = 0.0;     ///< rad, the arm-angle spare the turned end lacked
  bool line_unreachable = false;  ///< kPlainBlend: the line principle's grasp was tried too
  int side = 0;                   ///< kLinePrinciple: the side of the handle
  /// The bracket was blendable, but its blend failed its nominal trial in physics
  /// (bracket_reason says how).
  bool blend_failed = false;
  /// A library over placements (placement_motion.hpp): the query's cell, its vertices and
  /// weights in words, in place of the bracket; the vertex used (kTurnedDemo) or the vertices
  /// blended with their weights (kPartialBlend).
  std::string cell;
  std::string used_placement;

  /// The reason in words ("" for kNone): what could not be used, then what was.
  std::string Text() const;
};

/// Options of GenerateGraspingMotion.
struct MotionGenerationOptions {
  SynthesisMethod method = SynthesisMethod::kInterp;
  BracketOptions bracket;
  BlendOptions blend = {.waypoints = 40};
  /// rad, the feasible arm-angle arc a fallback's grasp and pre-grasp need on `branch`.
  double min_psi_width = Radians(10.0);
  /// The start configuration's branch, on which the fallbacks' reachability is judged.
  ArmBranch branch;
  /// The blend of this task's bracket failed its nominal trial in physics: the interp method
  /// takes the unblendable bracket's fallbacks (SynthesizeAndValidate sets it, and adds the
  /// trial's outcome to FallbackReason::bracket_reason).
  bool reject_blend = false;

  bool IsValid(std::string* why) const;
};

/// How the motion generation ended.
enum class MotionGenerationStatus {
  kOk,
  kOutOfRange,  ///< interp outside the library's range
  kNoModel,     ///< line: the line principle cannot be fitted on this library
};

/// The grasping motion and how it was made.
struct MotionGenerationResult {
  MotionGenerationStatus status = MotionGenerationStatus::kOk;
  std::string message;  ///< why, when not kOk
  SynthesisMethod used = SynthesisMethod::kInterp;
  FallbackReason fallback;  ///< kind kNone when the requested method was used
  int side = 0;             ///< side of the handle of the line-principle grasp (0: unused)
  Bracket bracket;
  std::vector<SourceDemo> sources;
  GraspingMotion motion;  ///< theta is the task's

  bool ok() const { return status == MotionGenerationStatus::kOk; }
};

/// The grasping motion for `task` by options.method (see the file comment). Options assumed
/// valid; failures are results.
MotionGenerationResult GenerateGraspingMotion(const SynthesisModel& model,
                                              const SynthesisTask& task,
                                              const MotionGenerationOptions& options);

/// A library entry's grasping motion turned with the object from its theta to `placement`'s
/// about the vertical through the object centre, and moved with it to placement.xy when that
/// is set.
GraspingMotion TurnWithObject(const GraspingMotion& motion, const Placement& placement);

/// True when the pre-grasp and grasp poses of `motion` keep `min_width` (rad) of feasible arm
/// angle on `branch`.
bool Reachable(const RobotModel& robot, const GraspingMotion& motion, ArmBranch branch,
               double min_width);

}  // namespace graspsynth
