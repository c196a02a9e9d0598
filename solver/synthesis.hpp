#pragma once

/// @file
/// Grasp synthesis for an object orientation absent from the library (paper section IV and
/// DESIGN.md's "generalize", "refine", "reach"), as a pipeline of stages, each a free function
/// with its own options and result:
/// 1. GenerateGraspingMotion (motion_generation.hpp): the grasping motion by one of three
///    methods, with the interp method's fallbacks and their typed reason;
/// 2. CheckStart: the start configuration (given, or the rest pose) within the joint limits
///    and free of collision;
/// 3. RefineSynthesizedMotion: the optional stages of the refinement: the thresholds loosened
///    to what the sources did (SourceThresholdsOptions), then the refinement stages named in
///    SynthesisOptions::refinement_stages (refinement.hpp: Ceres, then NLopt);
/// 4. PlanReach (reach_planning.hpp): the reach from the start to the pre-grasp, played with
///    the grasping motion and the lift (GraspAndLift) through the analytic IK with a
///    continuous arm angle;
/// 5. AssembleTrajectory: the robot's trajectory and its waypoints.
/// SynthesizeGrasp runs them in that order on one SynthesisTask, the object's placement
/// entered once and its pose X_WO computed once, which every stage reads; SynthesisOptions
/// says which optional stages run (studies/study_method.hpp builds it from a method's label).

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "collision/collision_scene.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/grasp_library.hpp"
#include "motion/interpolation.hpp"
#include "motion/joint_space.hpp"
#include "motion/reach.hpp"
#include "scene/scene_model.hpp"
#include "solver/bracket.hpp"
#include "solver/line_principle.hpp"
#include "solver/motion_generation.hpp"
#include "solver/reach_planning.hpp"
#include "solver/refinement.hpp"
#include "solver/synthesis_model.hpp"

namespace graspsynth {

/// The thresholds stage: the refinement's thresholds loosened to what the source
/// demonstrations did themselves: the clearance margin to their smallest approach clearance,
/// the penetration tolerance to their deepest grasp penetration, the contact tolerance to their
/// largest contact error, each only when the demonstration is outside the option's value. The
/// sources held the object in physics, so a geometric threshold they break is the model's, not
/// the grasp's, and enforcing it moves a working hold (measured on the shipped library: the
/// 20-40 deg representatives break the defaults). For the line principle, the nearest entry is
/// the source. It has no parameter: its presence in SynthesisOptions is the choice.
struct SourceThresholdsOptions {};

/// The grip slide: a grasp that holds the handle at its end is moved along the handle's axis
/// toward the object's centre, so that all of the hand's fingers hold the bar and the weight's
/// moment about the grip, which only friction couples between the fingertips resist (ODE has
/// no torsional friction), is smaller. The grip is the point of the handle's axis the hand
/// holds (the line principle's handle point in the hand, moved with the grasp); its radius is
/// its distance from the object's centre along the handle. A grip farther out than the
/// handle's end less tip_margin is slid in by the excess (at most max_distance), then by half
/// of it, `halvings` times; the first slide whose motion keeps the refinement's constraints
/// (with the thresholds the refinement used) and keeps the arm's links at least
/// min_arm_clearance from the object at the grasp is kept; none: the motion is kept. Objects
/// without a handle, and libraries without a fitted line principle, are not moved.
///
/// The default tip margin is half the span of the Gifu hand's four finger bases across the palm
/// (+-0.033 m, ../shared/reference/robot.md) plus a fingertip's half-width. The arm clearance
/// keeps the slide from bringing the forearm down onto the object's body (measured on the
/// placements grid: experiments/results/placements/levers/README.md).
struct GripSlideOptions {
  double tip_margin = 0.04;         ///< m, >= 0
  double max_distance = 0.05;       ///< m, > 0
  int halvings = 2;                 ///< >= 0
  double min_arm_clearance = 0.02;  ///< m, >= 0
};

/// The synthesis pipeline: each stage's options, in pipeline order. The optional stages run
/// when present: the thresholds stage when source_thresholds holds a value, each refinement
/// stage named in refinement_stages.
struct SynthesisOptions {
  /// 1. The grasping motion: method, bracket and blend (its resampling). Its min_psi_width is
  /// the refinement's and its branch the start's (set by SynthesizeGrasp).
  MotionGenerationOptions generation;
  /// 2. The start: arm configuration at the start, rad; unset: DefaultRestConfiguration for
  /// the grasp orientation. With the spline reach, the rest pose on another branch (the wrist
  /// flip first) when the motion cannot be played from the elbow-up one.
  std::optional<Vector7d> start;
  /// 3a. The thresholds stage: loosen the refinement's thresholds to what the source
  /// demonstrations did themselves (see SourceThresholdsOptions); std::nullopt: the
  /// refinement's own thresholds whatever the sources did. Without a refinement stage it
  /// changes nothing.
  std::optional<SourceThresholdsOptions> source_thresholds = SourceThresholdsOptions{};
  /// 3b. The refinement stages that run, in order (refinement.hpp's RefinementStages); empty:
  /// the generated motion is used as it is.
  RefinementStages refinement_stages = {RefinementStage::kCeres, RefinementStage::kNlopt};
  /// The parameters of the refinement stages (and of the thresholds they enforce).
  RefinementOptions refinement;
  /// 3c. The grip slide after the refinement stages (see GripSlideOptions); std::nullopt or no
  /// refinement stage: none.
  std::optional<GripSlideOptions> grip_slide;
  /// 4. The reach (its start_given is set by SynthesizeGrasp from `start`).
  ReachPlanOptions reach;
  /// The lift after the grasp; height and duration come from the sources' library entries
  /// (weighted) when they are positive there.
  LiftOptions lift;

  bool IsValid(std::string* why) const;

  /// True when at least one refinement stage runs.
  bool refines() const { return !refinement_stages.empty(); }
  /// The options of the generation and reach stages, with what they take from the others
  /// (the start's branch on `arm`, whose joints may turn against the DH table).
  MotionGenerationOptions Generation(const ArmModel& arm) const;
  ReachPlanOptions Reach() const;
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

/// The synthesized grasp.
struct SynthesisResult {
  SynthesisStatus status = SynthesisStatus::kUnreachable;
  std::string message;  ///< why, when not kOk
  double theta_deg = 0.0;
  Placement placement;  ///< the task's (xy empty: the scene's object centre)
  SynthesisMethod requested = SynthesisMethod::kInterp;
  SynthesisMethod used = SynthesisMethod::kInterp;
  bool fallback = false;           ///< a method other than the requested one was used
  FallbackReason fallback_reason;  ///< why, and what was tried (kind kNone: no fallback)
  int side = 0;                    ///< side of the handle of the line-principle grasp (0: unused)
  Bracket bracket;
  std::vector<SourceDemo> sources;
  GraspingMotion unrefined;  ///< the grasping motion before refinement
  GraspingMotion motion;     ///< the grasping motion after refinement (or unrefined)
  bool refined = false;
  /// The thresholds the refinement used (the thresholds stage applied), m.
  double clearance_margin = 0.0, penetration_tolerance = 0.0, contact_tolerance = 0.0;
  RefinementReport refinement;
  double grip_slide = 0.0;  ///< m the grip slide moved the motion toward the object's centre
  double grip_radius = std::numeric_limits<double>::quiet_NaN();  ///< m, before the grip slide
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

/// Options of CheckStart.
struct StartCheckOptions {
  /// Arm configuration at the start, rad; unset: DefaultRestConfiguration for the grasp
  /// orientation of the motion.
  std::optional<Vector7d> start;
};

/// The start configuration and whether it can be used.
struct StartCheckResult {
  bool ok = false;
  std::string message;                ///< why not, when not ok
  Vector7d start = Vector7d::Zero();  ///< the start configuration, rad
};

/// The start configuration of `motion` for `task`: options.start when given (each joint within
/// its limits), else the rest pose for the grasp orientation; free of collision with the
/// fingers in the pre-grasp shape and the object at task.X_WO.
StartCheckResult CheckStart(const SynthesisModel& model, const SynthesisTask& task,
                            const GraspingMotion& motion, const StartCheckOptions& options,
                            CollisionData* data);

/// Options of RefineSynthesizedMotion.
struct MotionRefinementOptions {
  RefinementOptions refinement;
  /// The thresholds stage (see SynthesisOptions); std::nullopt: the refinement's own.
  std::optional<SourceThresholdsOptions> source_thresholds = SourceThresholdsOptions{};
  /// The refinement stages, in order.
  RefinementStages stages = {RefinementStage::kCeres, RefinementStage::kNlopt};
};

/// The grip slide's motion, how far it moved toward the object's centre, m (0: not moved), and
/// the grip's radius before the slide, m (NaN: no handle or no line principle).
struct GripSlideResult {
  GraspingMotion motion;
  double distance = 0.0;
  double grip_radius = std::numeric_limits<double>::quiet_NaN();
};

/// The grip slide (GripSlideOptions) of `motion` for `task`, played from `q_start`, checked
/// against the refinement's constraints with `thresholds`' values.
GripSlideResult SlideGrip(const SynthesisModel& model, const SynthesisTask& task,
                          const GraspingMotion& motion, const Vector7d& q_start,
                          const RefinementOptions& thresholds, const GripSlideOptions& options,
                          CollisionData* data);

/// The refined motion, the refinement's report and the thresholds it used.
struct MotionRefinementResult {
  GraspingMotion motion;
  RefinementReport report;
  RefinementOptions used;  ///< the refinement's options, thresholds from the sources applied
};

/// The thresholds stage then the refinement stages (refinement.hpp) on the generated motion from
/// the start configuration `q_start`, with the line prior and contact constraint when the line
/// principle is fitted. The thresholds' sources: the generated motion's sources, or the nearest
/// entry for the line principle. The object stands at task.X_WO. Throws InputError for invalid
/// refinement options.
MotionRefinementResult RefineSynthesizedMotion(
    const SynthesisModel& model, const SynthesisTask& task, const MotionGenerationResult& generated,
    const GraspingMotion& motion, const Vector7d& q_start, const MotionRefinementOptions& options,
    CollisionData* data);

/// The tail of the robot's path after the pre-grasp: the grasping motion, then the lift.
struct GraspAndLiftPath {
  CartesianPath path;      ///< times from the pre-grasp
  size_t grasp_index = 0;  ///< the grasp pose's sample in `path`
  LiftOptions lift;        ///< the lift used (height and duration from the sources)
};

/// `motion` followed by the lift of `options`, its height and duration replaced by the
/// sources' weighted library figures where those are positive.
GraspAndLiftPath GraspAndLift(const GraspLibrary& library, const std::vector<SourceDemo>& sources,
                              const GraspingMotion& motion, const LiftOptions& options);

/// The robot's trajectory from a played reach (reach.ok()) and its tail: the joint samples,
/// the first one set to the start configuration exactly, with the waypoints start, pre-grasp,
/// grasp, lift start and top (those at a later time than the one before).
JointTrajectory AssembleTrajectory(const ReachPlanResult& reach, const GraspAndLiftPath& tail);

/// Synthesizes a grasp for object orientation `theta_deg`: the stages above, in order. Throws
/// InputError for invalid options; bad queries and failures are results. `data` is the
/// calling thread's workspace, made from `model`.
SynthesisResult SynthesizeGrasp(const SynthesisModel& model, double theta_deg,
                                const SynthesisOptions& options, SynthesisData* data);
/// The same for a task made by MakeSynthesisTask (the object at a placement of its own).
SynthesisResult SynthesizeGrasp(const SynthesisModel& model, const SynthesisTask& task,
                                const SynthesisOptions& options, SynthesisData* data);

}  // namespace graspsynth
