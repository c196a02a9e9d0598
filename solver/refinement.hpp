#pragma once

/// @file
/// Refinement of a synthesized grasping motion in two stages (DESIGN.md, "refine").
///
/// Stage 1, Ceres least squares over the waypoint positions p_i = b_i + d_i (b: the input
/// motion, d_i the correction; orientations and fingers are kept):
/// - fidelity to the input: d_i / fidelity_sigma;
/// - smoothness of the correction: (d_{i-1} - 2 d_i + d_{i+1}) / smoothness_sigma (the input,
///   a blend of smooth demonstrations, is smooth already: the correction must not add kinks);
/// - the line prior: the grasp position's distance from the wrist line (object-centred table
///   plane) / line_sigma, when a line is given;
/// - reachability through the IK: on every reach_stride-th waypoint and the last,
///   max(0, min_psi_width - w_i) / reach_sigma, w_i the widest feasible arm-angle arc of the
///   pose on the start configuration's branch (0 when it has none; numeric derivatives).
///
/// Stage 2, NLopt on the grasp pose and the finger closure: x = (shift dx, dy, dz of the whole
/// motion, m; yaw about the vertical through the grasp position, rad; closure c scaling every
/// finger's travel from the first waypoint's shape), objective (|d| / shift_scale)^2 +
/// (yaw / yaw_scale)^2 + ((c - 1) / closure_scale)^2 (stay close to stage 1), constraints:
/// - approach clearance: the signed distance of arm and hand from object and table >=
///   clearance_margin at the approach states (waypoints before the fingers start closing,
///   farther than contact_zone from where they start closing), arm from the IK;
/// - no penetration at the grasp: >= -penetration_tolerance at the approach states within
///   contact_zone and at the grasp pose with the fingers still in their approach shape (the
///   closed shape presses into the handle on purpose: that is the squeeze);
/// - contact: the handle's axis within contact_tolerance of the handle point the library holds
///   in the hand (line_principle.hpp), when one is given;
/// - joint limits: the widest feasible arm-angle arc of the pre-grasp and grasp poses >=
///   min_psi_width.
/// The stage runs only when the start is infeasible (otherwise the start is the optimum: the
/// objective is 0 there). SLSQP or MMA with forward-difference constraint gradients, COBYLA as
/// the fallback when the first one fails or ends infeasible.
///
/// A stage whose output violates the constraints more than its input is discarded, so the
/// refinement never turns a feasible motion infeasible. NLopt and Ceres stay in the .cpp.

#include <optional>
#include <string>
#include <vector>

#include "analysis/wrist_line.hpp"
#include "collision/collision_scene.hpp"
#include "kinematics/robot_description.hpp"
#include "motion/grasping_motion.hpp"
#include "scene/scene_model.hpp"

namespace graspsynth {

/// The NLopt algorithm of stage 2.
enum class NloptAlgorithm { kSlsqp, kMma, kCobyla };

/// "slsqp", "mma" or "cobyla".
const char* ToString(NloptAlgorithm algorithm);

/// Options of RefineGraspingMotion. Lengths in m, angles in rad.
struct RefinementOptions {
  double fidelity_sigma = 0.01;          ///< m
  double smoothness_sigma = 0.002;       ///< m
  double line_sigma = 0.05;              ///< m
  double reach_sigma = Radians(1.0);     ///< rad
  double min_psi_width = Radians(10.0);  ///< rad, also stage 2's joint-limit constraint
  int reach_stride = 5;                  ///< >= 1
  int ceres_max_iterations = 20;         ///< >= 1

  NloptAlgorithm algorithm = NloptAlgorithm::kSlsqp;
  bool cobyla_fallback = true;
  double clearance_margin = 0.005;       ///< m
  double penetration_tolerance = 0.002;  ///< m
  double contact_zone = 0.03;            ///< m
  double contact_tolerance = 0.01;       ///< m
  int approach_states = 8;               ///< far approach states checked (evenly chosen), >= 1
  int near_states = 4;                   ///< near states checked besides the grasp, >= 0
  /// The fingers start closing at the first waypoint where a finger has moved this far from
  /// its shape at the first waypoint, rad.
  double finger_start_threshold = Radians(2.0);
  double max_shift = 0.15;         ///< bound on |dx|, |dy|, |dz|, m
  double max_yaw = Radians(30.0);  ///< bound on |yaw|, rad
  double min_closure = 0.8, max_closure = 1.2;
  double shift_scale = 0.01;        ///< m
  double yaw_scale = Radians(5.0);  ///< rad
  double closure_scale = 0.1;
  int max_evaluations = 300;  ///< per algorithm, >= 1
  double xtol = 1e-5;         ///< relative tolerance on x

  bool IsValid(std::string* why) const;
};

/// What the refinement knows besides the motion.
struct RefinementInputs {
  /// The object's pose at rest (object frame O in world W) where the motion grasps it: the
  /// task's, computed once from its placement (SceneModel::ObjectPose). The constraints place
  /// the object here.
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
  /// Arm configuration the robot starts from: its branch is kept and its arm angle starts the
  /// IK along the motion.
  Vector7d q_start = Vector7d::Zero();
  /// The wrist line (object-centred table plane) for the line prior; none: no prior.
  std::optional<Line2d> wrist_line;
  /// Where the handle's axis lies in the hand frame H at the grasp (m); none: no contact
  /// constraint.
  std::optional<Eigen::Vector3d> handle_in_hand;
};

/// The constraint values of a motion (stage 2's constraints; evaluated for every report).
struct RefinementConstraints {
  double approach_clearance = 0.0;  ///< m, min over the far approach states (>= margin)
  double grasp_clearance = 0.0;     ///< m, min over the near states and the grasp (>= -tol)
  std::string closest_pair;         ///< the pair of the smaller of the two, in words
  /// m, the arm's links (the hand not counted) from the object at the grasp (not a constraint
  /// of the refinement; the grip slide keeps it). Distances beyond the larger of 5 cm and twice
  /// the clearance margin are reported as that bound or more.
  double arm_object_clearance = 0.0;
  double contact_error = 0.0;  ///< m (<= contact_tolerance); NaN without handle_in_hand
  double min_psi_width = 0.0;  ///< rad (>= min_psi_width)
  bool reachable = false;      ///< every checked pose has an IK solution on the branch
  int states = 0;              ///< states checked
  bool feasible = false;       ///< every constraint holds (to 1e-5 m)
  double violation = 0.0;      ///< sum of the violations, m (rad counted as 0.1 m per rad)
};

/// Ceres stage figures.
struct CeresStageReport {
  bool run = false;
  double initial_cost = 0.0, final_cost = 0.0;
  /// Final cost terms: 1/2 sum of squared residuals of each kind.
  double fidelity = 0.0, smoothness = 0.0, line = 0.0, reach = 0.0;
  double initial_reach = 0.0;  ///< the reachability term before
  int iterations = 0;
  std::string termination;
  double time_s = 0.0;
};

/// NLopt stage figures.
struct NloptStageReport {
  bool run = false;
  std::string algorithm;  ///< the algorithm whose result was kept
  bool fallback_used = false;
  std::string termination;  ///< NLopt's result code, or why the stage did not run
  int evaluations = 0;      ///< constraint evaluations, every algorithm together
  double initial_objective = 0.0, final_objective = 0.0;
  Eigen::Vector3d shift = Eigen::Vector3d::Zero();  ///< m
  double yaw = 0.0;                                 ///< rad
  double closure = 1.0;
  double time_s = 0.0;
};

/// A stage of the refinement: the one whose output RefineGraspingMotion returns.
enum class RefinementStage { kInput, kCeres, kNlopt };

/// "input", "ceres" or "nlopt".
const char* ToString(RefinementStage stage);

/// The refinement's report.
struct RefinementReport {
  CeresStageReport ceres;
  NloptStageReport nlopt;
  RefinementConstraints before;                    ///< of the input
  RefinementConstraints after_ceres;               ///< of stage 1's output
  RefinementConstraints after;                     ///< of the returned motion
  RefinementStage kept = RefinementStage::kInput;  ///< whose output is returned
  double time_s = 0.0;

  /// One line: constraint values before and after, costs, iterations, termination.
  std::string BriefReport() const;
};

/// The refined motion and the report.
struct RefinementResult {
  GraspingMotion motion;
  RefinementReport report;
};

/// The constraint values of `motion` (see the file comment).
RefinementConstraints EvaluateRefinementConstraints(
    const RobotModel& robot, const SceneModel& scene, const CollisionModel& collision,
    const GraspingMotion& motion, const RefinementInputs& inputs, const RefinementOptions& options,
    CollisionData* data);

/// `options` with the thresholds loosened to what the source demonstrations did themselves
/// (SynthesisOptions::source_thresholds, the thresholds stage): the clearance margin down to the
/// smallest approach clearance of `sources`, the penetration tolerance up to the deepest grasp
/// penetration, the contact tolerance up to the largest finite contact error; the other
/// fields unchanged.
RefinementOptions ThresholdsFromSources(const RefinementOptions& options,
                                        const std::vector<RefinementConstraints>& sources);

/// Stage 1's output: the motion with the corrections applied (the input when the solution is
/// not usable) and the figures.
struct CeresStageResult {
  GraspingMotion motion;
  CeresStageReport report;
  bool usable = false;  ///< Ceres' solution is usable (its corrections were applied)
};

/// Stage 1 alone (see the file comment): Ceres least squares over the waypoint positions of
/// `motion` (well formed), with options' fidelity, smoothness, line and reach terms (options
/// assumed valid). Orientations, fingers and times are kept; the constraints are not checked.
CeresStageResult RunCeresStage(const RobotModel& robot, const GraspingMotion& motion,
                               const RefinementInputs& inputs, const RefinementOptions& options);

/// Stage 2's output: the moved motion, its constraint values and the figures.
struct NloptStageResult {
  GraspingMotion motion;
  RefinementConstraints constraints;  ///< of `motion`
  NloptStageReport report;
};

/// Stage 2 alone (see the file comment): NLopt on the shift, yaw and closure of `motion`
/// (options assumed valid), with the COBYLA fallback when options say so. Runs whatever the
/// start's feasibility; an optimizer that fails is reported, never thrown.
NloptStageResult RunNloptStage(const RobotModel& robot, const SceneModel& scene,
                               const CollisionModel& collision, const GraspingMotion& motion,
                               const RefinementInputs& inputs, const RefinementOptions& options,
                               CollisionData* data);

/// The stages RefineGraspingMotion runs, in the order they run: kCeres, then kNlopt, each at
/// most once (kInput is not a stage). The default runs both.
using RefinementStages = std::vector<RefinementStage>;

/// True when `stages` names kCeres and kNlopt at most once each, in that order, and nothing
/// else; otherwise false with the reason in `why`.
bool IsValidRefinementStages(const RefinementStages& stages, std::string* why);

/// Refines `motion` (well formed) by `stages` in order (a stage absent from it does not run).
/// Throws InputError for invalid options or stages; an optimizer that fails is reported, never
/// thrown.
RefinementResult RefineGraspingMotion(const RobotModel& robot, const SceneModel& scene,
                                      const CollisionModel& collision, const GraspingMotion& motion,
                                      const RefinementInputs& inputs,
                                      const RefinementOptions& options, CollisionData* data,
                                      const RefinementStages& stages = {RefinementStage::kCeres,
                                                                        RefinementStage::kNlopt});

}  // namespace graspsynth
