#pragma once

/// @file
/// The reach stage of the synthesis (synthesis.hpp): how the robot gets from the start
/// configuration to the pre-grasp pose, played together with the grasping motion and the lift
/// (the tail) into one joint trajectory.

#include <string>

#include "motion/joint_space.hpp"
#include "motion/reach.hpp"
#include "solver/synthesis_model.hpp"

namespace graspsynth {

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

/// "spline", "joint" or "auto".
const char* ToString(ReachMethod method);
/// Parses "spline", "joint" or "auto"; throws InputError naming the value otherwise.
ReachMethod ParseReachMethod(const std::string& text);

/// Options of PlanReach.
struct ReachPlanOptions {
  ReachMethod method = ReachMethod::kAuto;
  SplineReachOptions spline;
  JointReachOptions joint;
  /// m, the wrist displacement along each world axis every spline-reach pose must survive for
  /// kAuto to keep the spline.
  double margin = 0.01;
  JointSpaceOptions joint_space;
  /// The start was given by the user: kept as it is. Otherwise (the default rest pose), the
  /// spline reach may start from the rest pose on another branch (the wrist flip first) when
  /// the elbow-up one cannot play the motion.
  bool start_given = false;
};

/// The reach and the joint trajectory of reach + tail.
struct ReachPlanResult {
  /// A reach was chosen (played or not); false when the joint reach failed and no spline was
  /// playable.
  bool chosen = false;
  ReachMethod used = ReachMethod::kSpline;  ///< kSpline or kJoint, when chosen
  std::string reason;                       ///< why that reach, in words
  Vector7d start = Vector7d::Zero();        ///< the start configuration the reach leaves from
  CartesianPath path;                       ///< reach + tail (the joint reach's by FK)
  size_t reach_samples = 0;                 ///< path samples of the reach, pre-grasp included
  JointSpaceResult joints;                  ///< the joint conversion of `path`

  /// A reach was chosen and its trajectory plays.
  bool ok() const { return chosen && joints.status == JointSpaceStatus::kOk; }
};

/// The reach from `q_start` to the pre-grasp of `motion` (well formed) followed by `tail` (the
/// grasping motion and the lift, times from the pre-grasp), by options.method (see
/// ReachMethod). Collision checks place the object at task.X_WO; `data` is made from
/// model.collision(). Failures are results.
ReachPlanResult PlanReach(const SynthesisModel& model, const SynthesisTask& task,
                          const GraspingMotion& motion, const CartesianPath& tail,
                          const Vector7d& q_start, const ReachPlanOptions& options,
                          CollisionData* data);

}  // namespace graspsynth
