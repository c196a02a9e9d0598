#include "solver/synthesis.hpp"

#include <chrono>
#include <cmath>
#include <sstream>

#include "common/errors.hpp"
#include "common/stopwatch.hpp"
#include "common/valid_options.hpp"
#include "scene/rest_pose.hpp"

namespace graspsynth {

namespace {

using Clock = WallClock;

// The motion generation's outcome copied into the synthesis result.
void TakeGeneration(const MotionGenerationResult& g, SynthesisResult* r) {
  r->used = g.used;
  r->fallback = g.fallback.kind != FallbackKind::kNone;
  r->fallback_reason = g.fallback;
  r->side = g.side;
  r->bracket = g.bracket;
  r->sources = g.sources;
  if (g.status == MotionGenerationStatus::kOutOfRange) r->status = SynthesisStatus::kOutOfRange;
  if (g.status == MotionGenerationStatus::kNoModel) r->status = SynthesisStatus::kNoModel;
  r->message = g.message;
}

}  // namespace

const char* ToString(SynthesisStatus status) {
  switch (status) {
    case SynthesisStatus::kOk:
      return "ok";
    case SynthesisStatus::kOutOfRange:
      return "out_of_range";
    case SynthesisStatus::kBadStart:
      return "bad_start";
    case SynthesisStatus::kNoModel:
      return "no_model";
    case SynthesisStatus::kUnreachable:
      return "unreachable";
  }
  return "?";
}

bool SynthesisOptions::IsValid(std::string* why) const {
  const ReachPlanOptions r = Reach();
  if (!generation.IsValid(why) || !IsValidRefinementStages(refinement_stages, why) ||
      !refinement.IsValid(why) || !r.spline.IsValid(why) || !lift.IsValid(why) ||
      !r.joint_space.IsValid(why)) {
    return false;
  }
  if (!(r.margin >= 0.0)) {
    if (why) *why = "reach_margin must be >= 0";
    return false;
  }
  if (!r.joint.IsValid(why)) return false;
  if (start && !start->allFinite()) {
    if (why) *why = "start must be finite when given";
    return false;
  }
  if (grip_slide) {
    const GripSlideOptions& g = *grip_slide;
    if (!(std::isfinite(g.tip_margin) && std::isfinite(g.max_distance) &&
          std::isfinite(g.min_arm_clearance) && g.tip_margin >= 0.0 && g.max_distance > 0.0 &&
          g.halvings >= 0 && g.min_arm_clearance >= 0.0)) {
      if (why) {
        *why =
            "the grip slide needs tip_margin >= 0, max_distance > 0, halvings >= 0 and "
            "min_arm_clearance >= 0";
      }
      return false;
    }
  }
  return true;
}

MotionGenerationOptions SynthesisOptions::Generation(const ArmModel& arm) const {
  MotionGenerationOptions o = generation;
  o.min_psi_width = refinement.min_psi_width;
  o.branch = start ? BranchOf(arm, *start) : ArmBranch{};
  return o;
}

ReachPlanOptions SynthesisOptions::Reach() const {
  ReachPlanOptions o = reach;
  o.start_given = start.has_value();
  return o;
}

StartCheckResult CheckStart(const SynthesisModel& model, const SynthesisTask& task,
                            const GraspingMotion& motion, const StartCheckOptions& options,
                            CollisionData* data) {
  const RobotModel& robot = model.robot();
  StartCheckResult r;
  if (options.start) {
    const Vector7d& q = *options.start;
    for (int j = 0; j < kArmDof; ++j) {
      // written so that a NaN joint is outside its limits too
      if (!(q[j] >= robot.arm.lower()[j] && q[j] <= robot.arm.upper()[j])) {
        std::ostringstream s;
        s << "start configuration: joint " << j + 1 << " = " << q[j]
          << " rad is outside its limits [" << robot.arm.lower()[j] << ", " << robot.arm.upper()[j]
          << "]";
        r.message = s.str();
        return r;
      }
    }
    r.start = q;
  } else {
    r.start =
        DefaultRestConfiguration(robot, model.scene(), motion.grasp().q_WH.toRotationMatrix());
  }
  SetState(model.collision(), r.start, motion.pregrasp().f, task.X_WO, data);
  CollideOptions co;
  co.max_pairs = 1;
  const CollisionReport hit =
      Collide(model.collision(), GroupSet::Robot(), GroupSet::World(), data, co);
  if (hit.collision()) {
    r.message = "start configuration is in collision: " + hit.BriefReport();
    return r;
  }
  r.ok = true;
  return r;
}

namespace {

// What the refinement knows about `task` besides the motion.
RefinementInputs TaskRefinementInputs(const SynthesisModel& model, const SynthesisTask& task,
                                      const Vector7d& q_start) {
  RefinementInputs in;
  in.X_WO = task.X_WO;
  in.q_start = q_start;
  if (model.line().valid) {
    in.wrist_line = model.line().wrist_line.line;
    in.handle_in_hand = model.line().handle_in_hand;
  }
  return in;
}

}  // namespace

GripSlideResult SlideGrip(const SynthesisModel& model, const SynthesisTask& task,
                          const GraspingMotion& motion, const Vector7d& q_start,
                          const RefinementOptions& thresholds, const GripSlideOptions& options,
                          CollisionData* data) {
  GripSlideResult r{motion};
  const ObjectModel& object = model.scene().object;
  if (!object.handle || !model.line().valid) return r;
  const Eigen::Vector3d along = object.HandleDirection(task.X_WO);
  const Eigen::Vector3d grip = WaypointPose(motion.grasp()) * model.line().handle_in_hand;
  r.grip_radius = (grip - task.X_WO.translation()).dot(along);
  double d = std::min(options.max_distance,
                      r.grip_radius - (object.handle->end_radius - options.tip_margin));
  if (!(d > 0.0)) return r;
  const RefinementInputs in = TaskRefinementInputs(model, task, q_start);
  for (int k = 0; k <= options.halvings; ++k, d *= 0.5) {
    GraspingMotion moved = motion;
    for (MotionWaypoint& w : moved.waypoints) w.p_WH -= d * along;
    const RefinementConstraints c = EvaluateRefinementConstraints(
        model.robot(), model.scene(), model.collision(), moved, in, thresholds, data);
    if (c.feasible && c.arm_object_clearance >= options.min_arm_clearance) {
      r.motion = std::move(moved);
      r.distance = d;
      return r;
    }
  }
  return r;
}

MotionRefinementResult RefineSynthesizedMotion(
    const SynthesisModel& model, const SynthesisTask& task, const MotionGenerationResult& generated,
    const GraspingMotion& motion, const Vector7d& q_start, const MotionRefinementOptions& options,
    CollisionData* data) {
  const RefinementInputs in = TaskRefinementInputs(model, task, q_start);
  MotionRefinementResult r;
  r.used = options.refinement;
  if (options.source_thresholds) {
    std::vector<RefinementConstraints> sources;
    if (generated.used == SynthesisMethod::kLine) {
      sources.push_back(model.entry_constraints()[generated.bracket.nearest]);
    } else {
      for (const SourceDemo& s : generated.sources) {
        sources.push_back(model.entry_constraints()[s.entry]);
      }
    }
    r.used = ThresholdsFromSources(options.refinement, sources);
  }
  RefinementResult rr = RefineGraspingMotion(model.robot(), model.scene(), model.collision(),
                                             motion, in, r.used, data, options.stages);
  r.motion = std::move(rr.motion);
  r.report = std::move(rr.report);
  return r;
}

GraspAndLiftPath GraspAndLift(const GraspLibrary& library, const std::vector<SourceDemo>& sources,
                              const GraspingMotion& motion, const LiftOptions& options) {
  GraspAndLiftPath tail;
  tail.path.assign(motion.waypoints.begin(), motion.waypoints.end());
  tail.grasp_index = tail.path.size() - 1;
  tail.lift = options;
  double height = 0.0, duration = 0.0;
  for (const SourceDemo& s : sources) {
    height += s.weight * library.entries[s.entry].lift_height;
    duration += s.weight * library.entries[s.entry].lift_duration;
  }
  if (height > 0.0) tail.lift.height = height;
  if (duration > 0.0) tail.lift.duration = duration;
  const CartesianPath up = LiftPath(tail.path.back(), tail.lift);
  tail.path.insert(tail.path.end(), up.begin(), up.end());
  return tail;
}

JointTrajectory AssembleTrajectory(const ReachPlanResult& reach, const GraspAndLiftPath& tail) {
  const CartesianPath& path = reach.path;
  const size_t i_pre = reach.reach_samples - 1;
  const size_t i_grasp = i_pre + tail.grasp_index;
  size_t i_top = path.size() - 1;
  for (size_t i = i_grasp; i < path.size(); ++i) {
    if (path[i].p_WH.z() >= path[i_grasp].p_WH.z() + tail.lift.height - 1e-9) {
      i_top = i;
      break;
    }
  }
  size_t i_lift = i_grasp;
  while (i_lift + 1 < path.size() && path[i_lift + 1].p_WH.z() <= path[i_grasp].p_WH.z() + 1e-9) {
    ++i_lift;
  }
  JointTrajectory trajectory = reach.joints.trajectory;
  trajectory.samples.front().arm = reach.start;
  trajectory.waypoints.clear();
  for (size_t i : {size_t{0}, i_pre, i_grasp, i_lift, i_top}) {
    if (!trajectory.waypoints.empty() && trajectory.samples[i].t <= trajectory.waypoints.back().t) {
      continue;
    }
    WristWaypoint w;
    w.t = trajectory.samples[i].t;
    w.p_WH = path[i].p_WH;
    w.q_WH = path[i].q_WH.normalized();
    trajectory.waypoints.push_back(w);
  }
  return trajectory;
}

SynthesisResult SynthesizeGrasp(const SynthesisModel& model, double theta_deg,
                                const SynthesisOptions& options, SynthesisData* workspace) {
  return SynthesizeGrasp(model, MakeSynthesisTask(model.scene(), theta_deg), options, workspace);
}

SynthesisResult SynthesizeGrasp(const SynthesisModel& model, const SynthesisTask& task,
                                const SynthesisOptions& options, SynthesisData* workspace) {
  RequireValid(options, "invalid synthesis option");
  CollisionData* data = workspace->collision();
  SynthesisResult r;
  r.theta_deg = task.theta_deg;
  r.placement = task.placement;
  r.requested = options.generation.method;

  // 1. the grasping motion.
  const auto t_generate = Clock::now();
  const MotionGenerationResult generated =
      GenerateGraspingMotion(model, task, options.Generation(model.robot().arm));
  TakeGeneration(generated, &r);
  if (!generated.ok()) return r;
  r.unrefined = generated.motion;
  r.generate_s = SecondsSince(t_generate);

  // 2. the start configuration.
  const StartCheckResult start = CheckStart(model, task, generated.motion, {options.start}, data);
  if (!start.ok) {
    r.status = SynthesisStatus::kBadStart;
    r.message = start.message;
    return r;
  }
  r.start = start.start;

  // 3. refinement.
  const auto t_refine = Clock::now();
  r.motion = generated.motion;
  RefinementOptions used = options.refinement;
  if (options.refines()) {
    MotionRefinementResult refined = RefineSynthesizedMotion(
        model, task, generated, generated.motion, r.start,
        {options.refinement, options.source_thresholds, options.refinement_stages}, data);
    used = refined.used;
    r.clearance_margin = refined.used.clearance_margin;
    r.penetration_tolerance = refined.used.penetration_tolerance;
    r.contact_tolerance = refined.used.contact_tolerance;
    r.motion = std::move(refined.motion);
    r.refinement = std::move(refined.report);
    r.refined = true;
  }
  if (options.grip_slide && options.refines()) {
    const GripSlideResult slid =
        SlideGrip(model, task, r.motion, r.start, used, *options.grip_slide, data);
    r.motion = slid.motion;
    r.grip_slide = slid.distance;
    r.grip_radius = slid.grip_radius;
  }
  r.refine_s = SecondsSince(t_refine);

  // 4. reach, grasping motion, lift, joints.
  const auto t_joints = Clock::now();
  const GraspAndLiftPath tail = GraspAndLift(model.library(), r.sources, r.motion, options.lift);
  ReachPlanResult reach =
      PlanReach(model, task, r.motion, tail.path, r.start, options.Reach(), data);
  r.joints_s = SecondsSince(t_joints);
  r.reach_reason = reach.reason;
  if (!reach.ok()) {
    r.status = SynthesisStatus::kUnreachable;
    r.message = "the synthesized motion cannot be played from the start configuration: " +
                (reach.chosen ? reach.joints.message : r.reach_reason);
    if (reach.chosen) r.joints = reach.joints;
    return r;
  }

  // 5. the trajectory.
  r.start = reach.start;
  r.reach_used = reach.used;
  r.trajectory = AssembleTrajectory(reach, tail);
  r.trajectory.object_xy = task.placement.xy;
  r.path = std::move(reach.path);
  r.joints = std::move(reach.joints);
  r.status = SynthesisStatus::kOk;
  return r;
}

}  // namespace graspsynth
