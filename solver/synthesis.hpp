#pragma once

/// @file
/// Grasp synthesis for an object orientation absent from the library (paper section IV and
/// DESIGN.md's "generalize", "refine", "reach"): a grasping motion by one of three methods, the
/// refinement (refinement.hpp), a spline reach from the start configuration, the lift, and the
/// joint trajectory through the analytic IK with a continuous arm angle.
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
///   left to the refinement. The result says which and why.
/// - nearest: the nearest demonstration turned with the object (any theta).
/// - line: the line principle (line_principle.hpp) on the nearest demonstration's side (any
///   theta).

#include <string>
#include <vector>

#include "collision/collision_scene.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/scene_model.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/interpolation.hpp"
#include "motion/joint_space.hpp"
#include "motion/reach.hpp"
#include "solver/bracket.hpp"
#include "solver/line_principle.hpp"
#include "solver/refinement.hpp"

namespace graspsynth {

/// How the grasping motion is made.
enum class SynthesisMethod { kInterp, kLine, kNearest };

/// How the robot reaches the pre-grasp pose from the start configuration.
/// - spline: the paper's reach (IV-C), a cubic spline of the wrist position with slerp
///   orientation, played through the IK on the start's branch;
/// - joint: a minimum-jerk move in joint space to the pre-grasp configuration (motion/
///   joint_space.hpp's JointReach); the grasping motion is played on the start's branch when
///   it can be, else on the first other branch that can play it; the move is checked for
///   collision;
/// - auto: the spline when every one of its poses stays reachable with the wrist moved by
///   reach_margin along each world axis (a reach near the edge of the workspace fails under
///   the perturbations of the physics gate), else the joint reach.
enum class ReachMethod { kSpline, kJoint, kAuto };

/// "interp", "line" or "nearest".
const char* ToString(SynthesisMethod method);
/// Parses "interp", "line" or "nearest"; throws InputError naming the value otherwise.
SynthesisMethod ParseSynthesisMethod(const std::string& text);

/// "spline", "joint" or "auto".
const char* ToString(ReachMethod method);
/// Parses "spline", "joint" or "auto"; throws InputError naming the value otherwise.
ReachMethod ParseReachMethod(const std::string& text);

/// Everything the synthesis needs that does not change between queries (STYLE.md's Model):
/// robot, scene, collision model, library and the line-principle models fitted over it.
class SynthesisModel {
 public:
  /// Checks the library (at least one entry, theta strictly increasing, every motion well
  /// formed; throws InputError naming the entry otherwise) and fits the line principle.
  SynthesisModel(RobotModel robot, SceneModel scene, GraspLibrary library,
                 const LinePrincipleOptions& line_options = {});

  const RobotModel& robot() const { return robot_; }
  const SceneModel& scene() const { return scene_; }
  const CollisionModel& collision() const { return collision_; }
  const GraspLibrary& library() const { return library_; }
  const LinePrincipleModel& line() const { return line_; }
  /// The refinement's constraint values of each library entry's own motion (from the rest pose
  /// for its grasp orientation), in entry order: what the demonstrations that held the object
  /// in physics did (SynthesisOptions::thresholds_from_sources).
  const std::vector<RefinementConstraints>& entry_constraints() const { return entry_constraints_; }
  /// The library's range, deg.
  double theta_min_deg() const { return library_.entries.front().theta_deg; }
  double theta_max_deg() const { return library_.entries.back().theta_deg; }

 private:
  RobotModel robot_;
  SceneModel scene_;
  GraspLibrary library_;
  CollisionModel collision_;
  LinePrincipleModel line_;
  std::vector<RefinementConstraints> entry_constraints_;
};

/// Options of SynthesizeGrasp.
struct SynthesisOptions {
  SynthesisMethod method = SynthesisMethod::kInterp;
  bool refine = true;
  BracketOptions bracket;
  BlendOptions blend = {.waypoints = 40};
  RefinementOptions refinement;
  /// Loosen the refinement's thresholds to what the source demonstrations did themselves: the
  /// clearance margin to their smallest approach clearance, the penetration tolerance to their
  /// deepest grasp penetration, the contact tolerance to their largest contact error, each only
  /// when the demonstration is outside the option's value. The sources held the object in
  /// physics, so a geometric threshold they break is the model's, not the grasp's, and
  /// enforcing it moves a working hold (measured on the shipped library: the 20-40 deg
  /// representatives break the defaults). For the line principle, the nearest entry is the
  /// source.
  bool thresholds_from_sources = true;
  ReachMethod reach_method = ReachMethod::kAuto;
  SplineReachOptions reach;
  JointReachOptions joint_reach;
  /// m, the wrist displacement along each world axis every spline-reach pose must survive for
  /// ReachMethod::kAuto to keep the spline.
  double reach_margin = 0.01;
  /// The lift after the grasp; height and duration come from the sources' library entries
  /// (weighted) when they are positive there.
  LiftOptions lift;
  JointSpaceOptions joint_space;
  /// Arm configuration at the start, rad; all NaN: DefaultRestConfiguration for the grasp
  /// orientation. With the spline reach, the rest pose on another branch (the wrist flip
  /// first) when the motion cannot be played from the elbow-up one.
  Vector7d start = Vector7d::Constant(NAN);

  bool IsValid(std::string* why) const;
};

/// How a synthesis ended.
enum class SynthesisStatus {
  kOk,
  kOutOfRange,   ///< interp outside the library's range
  kBadStart,     ///< the start configuration is outside the joint limits or in collision
  kNoModel,      ///< the line principle cannot be fitted on this library
  kUnreachable,  ///< the joint conversion failed (a pose without IK solution, or a jump)
};

/// "ok", "out_of_range", "bad_start", "no_model" or "unreachable".
const char* ToString(SynthesisStatus status);

/// A demonstration the grasp was made from.
struct SourceDemo {
  int entry = -1;  ///< library entry index
  double theta_deg = 0.0;
  std::string file;
  std::string trial;
  double weight = 0.0;  ///< its share in the grasp (blend weights sum to 1)
};

/// The synthesized grasp.
struct SynthesisResult {
  SynthesisStatus status = SynthesisStatus::kUnreachable;
  std::string message;  ///< why, when not kOk
  double theta_deg = 0.0;
  SynthesisMethod requested = SynthesisMethod::kInterp;
  SynthesisMethod used = SynthesisMethod::kInterp;
  bool fallback = false;        ///< a method other than the requested one was used
  std::string fallback_reason;  ///< why, and what was tried
  int side = 0;                 ///< side of the handle of the line-principle grasp (0: unused)
  Bracket bracket;
  std::vector<SourceDemo> sources;
  GraspingMotion unrefined;  ///< the grasping motion before refinement
  GraspingMotion motion;     ///< the grasping motion after refinement (or unrefined)
  bool refined = false;
  /// The thresholds the refinement used (thresholds_from_sources applied), m.
  double clearance_margin = 0.0, penetration_tolerance = 0.0, contact_tolerance = 0.0;
  RefinementReport refinement;
  Vector7d start = Vector7d::Zero();
  ReachMethod reach_used = ReachMethod::kSpline;  ///< kSpline or kJoint
  std::string reach_reason;                       ///< why that reach, in words
  CartesianPath path;          ///< reach + grasping motion + lift (the joint reach's by FK)
  JointSpaceResult joints;     ///< the joint conversion
  JointTrajectory trajectory;  ///< the robot's trajectory (waypoints: start, pre-grasp, grasp,
                               ///< lift start, top)
  double generate_s = 0.0, refine_s = 0.0, joints_s = 0.0;  ///< wall time of the stages

  bool ok() const { return status == SynthesisStatus::kOk; }
};

/// Synthesizes a grasp for object orientation `theta_deg`. Throws InputError for invalid
/// options; bad queries and failures are results. `data` is the caller's collision data
/// (made from model.collision()).
SynthesisResult SynthesizeGrasp(const SynthesisModel& model, double theta_deg,
                                const SynthesisOptions& options, CollisionData* data);

/// A library entry's grasping motion turned with the object from its theta to `theta` (rad)
/// about the vertical through the object centre.
GraspingMotion TurnWithObject(const GraspingMotion& motion, double theta);

}  // namespace graspsynth
