#include "solver/synthesis.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/rest_pose.hpp"

namespace graspsynth {

namespace {

constexpr double kDeg = M_PI / 180.0;

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Eigen::Isometry3d PoseOf(const MotionWaypoint& w) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = w.q_WH.toRotationMatrix();
  X.translation() = w.p_WH;
  return X;
}

double PsiWidth(const RobotModel& robot, const Eigen::Isometry3d& X_WH, ArmBranch branch) {
  const ArmTargetForm form = PrepareArmTarget(robot.arm, X_WH * robot.X_FH.inverse(), branch.gc4);
  if (form.status != IkStatus::kOk) return 0.0;
  const std::optional<Interval> widest =
      WidestInterval(FeasibleArmAngles(robot.arm, form, branch.gc2, branch.gc6));
  return widest ? widest->width() : 0.0;
}

// True when the pre-grasp and grasp poses keep `min_width` of feasible arm angle on `branch`.
bool Reachable(const RobotModel& robot, const GraspingMotion& m, ArmBranch branch,
               double min_width) {
  return PsiWidth(robot, PoseOf(m.pregrasp()), branch) >= min_width &&
         PsiWidth(robot, PoseOf(m.grasp()), branch) >= min_width;
}

SourceDemo Source(const GraspLibrary& library, int i, double weight) {
  const LibraryEntry& e = library.entries[i];
  return {i, e.theta_deg, e.file, e.trial, weight};
}

std::string Degrees(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// True when the robot at (q, f) touches the table or the object at its rest pose.
bool InCollision(const SynthesisModel& model, const Vector7d& q, const HandVector& f, double theta,
                 CollisionData* data) {
  SetState(model.collision(), q, f, theta, data);
  CollideOptions co;
  co.max_pairs = 1;
  return Collide(model.collision(), GroupSet::Robot(), GroupSet::World(), data, co).collision();
}

// A reach followed by `tail` (grasping motion and lift, times from the pre-grasp) as one
// Cartesian path and its joint trajectory.
struct ReachAttempt {
  ReachMethod method = ReachMethod::kSpline;
  CartesianPath path;
  size_t reach_samples = 0;  // path samples of the reach, pre-grasp included
  JointSpaceResult joints;
  int margin_failed_sample = -1;  // spline: the first reach pose that fails the margin test

  bool ok() const { return joints.status == JointSpaceStatus::kOk; }
  // spline: playable, and every reach pose survives the margin test.
  bool margin_ok() const { return ok() && margin_failed_sample < 0; }
};

// `tail` shifted to start at `t0`, its first sample (the pre-grasp) left out.
void AppendTail(const CartesianPath& tail, double t0, CartesianPath* path) {
  for (size_t i = 1; i < tail.size(); ++i) {
    MotionWaypoint w = tail[i];
    w.t += t0;
    path->push_back(w);
  }
}

// The first reach pose (index) that has no feasible arm angle on `branch` once the wrist moves
// by +-margin along a world axis, or -1.
int FirstPoseWithoutMargin(const RobotModel& robot, const CartesianPath& path, size_t count,
                           ArmBranch branch, double margin) {
  for (size_t i = 0; i < count; ++i) {
    for (int axis = 0; axis < 3; ++axis) {
      for (double sign : {-1.0, 1.0}) {
        Eigen::Isometry3d X = PoseOf(path[i]);
        X.translation()[axis] += sign * margin;
        if (PsiWidth(robot, X, branch) <= 0.0) return static_cast<int>(i);
      }
    }
  }
  return -1;
}

ReachAttempt SplineReachAttempt(const RobotModel& robot, const GraspingMotion& motion,
                                const CartesianPath& tail, const Vector7d& q_start,
                                double theta_deg, const SynthesisOptions& options) {
  ReachAttempt a;
  a.method = ReachMethod::kSpline;
  MotionWaypoint start;
  const Eigen::Isometry3d X_start = ArmFlangePose(robot.arm, q_start) * robot.X_FH;
  start.p_WH = X_start.translation();
  start.q_WH = Eigen::Quaterniond(X_start.linear()).normalized();
  start.f = motion.pregrasp().f;
  const MotionWaypoint& w0 = motion.waypoints[0];
  const MotionWaypoint& w1 = motion.waypoints[1];
  const Eigen::Vector3d v_end = (w1.p_WH - w0.p_WH) / std::max(1e-6, w1.t - w0.t);
  a.path = SplineReach(start, motion.pregrasp(), v_end, options.reach);
  a.reach_samples = a.path.size();
  AppendTail(tail, a.path.back().t, &a.path);
  a.joints = ToJointTrajectory(robot, a.path, q_start, theta_deg, options.joint_space);
  if (a.ok()) {
    a.margin_failed_sample = FirstPoseWithoutMargin(robot, a.path, a.reach_samples,
                                                    BranchOf(q_start), options.reach_margin);
  }
  return a;
}

// The joint reach: the grasping motion and lift played from the pre-grasp configuration on the
// start's branch, or the first other branch (the wrist flip first) that plays them, and a
// collision-free minimum-jerk move to it. std::nullopt, with the reason in `why`, when no
// branch works; on success `why` names the branch.
std::optional<ReachAttempt> JointReachAttempt(const SynthesisModel& model,
                                              const GraspingMotion& motion,
                                              const CartesianPath& tail, const Vector7d& q_start,
                                              double theta, double theta_deg,
                                              const SynthesisOptions& options, CollisionData* data,
                                              std::string* why) {
  const RobotModel& robot = model.robot();
  const int start_branch = BranchOf(q_start).index();
  const double psi = ArmAngleOf(robot.arm, q_start);
  std::ostringstream failures;
  std::vector<int> order = {start_branch};
  for (int index : {0, 4, 1, 5, 2, 6, 3, 7}) {
    if (index != start_branch) order.push_back(index);
  }
  for (int index : order) {
    const std::optional<Vector7d> q_pre =
        SolveWristPose(robot, PoseOf(motion.pregrasp()), ArmBranch::FromIndex(index), psi, q_start,
                       options.joint_space.psi_margin);
    if (!q_pre) continue;
    JointSpaceResult after = ToJointTrajectory(robot, tail, *q_pre, theta_deg, options.joint_space);
    if (after.status != JointSpaceStatus::kOk) continue;
    const std::vector<TrajectorySample> reach = JointReach(
        robot, q_start, motion.pregrasp().f, *q_pre, motion.pregrasp().f, options.joint_reach);
    int hit = -1;
    for (size_t k = 0; k < reach.size() && hit < 0; ++k) {
      if (InCollision(model, reach[k].arm, reach[k].hand, theta, data)) hit = static_cast<int>(k);
    }
    if (hit >= 0) {
      failures << " branch " << index << ": the move collides at t = " << reach[hit].t << " s;";
      continue;
    }
    ReachAttempt a;
    a.method = ReachMethod::kJoint;
    for (const TrajectorySample& s : reach) {
      const Eigen::Isometry3d X = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
      MotionWaypoint w;
      w.t = s.t;
      w.p_WH = X.translation();
      w.q_WH = Eigen::Quaterniond(X.linear()).normalized();
      w.f = s.hand;
      a.path.push_back(w);
    }
    a.path.back() = tail.front();
    a.path.back().t = reach.back().t;
    a.reach_samples = a.path.size();
    AppendTail(tail, reach.back().t, &a.path);
    a.joints = std::move(after);
    a.joints.trajectory.samples.erase(a.joints.trajectory.samples.begin());
    for (TrajectorySample& s : a.joints.trajectory.samples) s.t += reach.back().t;
    a.joints.trajectory.samples.insert(a.joints.trajectory.samples.begin(), reach.begin(),
                                       reach.end());
    for (size_t k = 1; k < reach.size(); ++k) {
      a.joints.max_joint_step = std::max(a.joints.max_joint_step,
                                         (reach[k].arm - reach[k - 1].arm).cwiseAbs().maxCoeff());
    }
    std::ostringstream s;
    s << " on branch " << index << " (" << reach.back().t << " s)";
    *why = s.str();
    return a;
  }
  *why = "no branch plays the grasping motion from a collision-free joint move;" + failures.str();
  return std::nullopt;
}

}  // namespace

const char* ToString(ReachMethod method) {
  switch (method) {
    case ReachMethod::kSpline:
      return "spline";
    case ReachMethod::kJoint:
      return "joint";
    case ReachMethod::kAuto:
      return "auto";
  }
  return "?";
}

ReachMethod ParseReachMethod(const std::string& text) {
  if (text == "spline") return ReachMethod::kSpline;
  if (text == "joint") return ReachMethod::kJoint;
  if (text == "auto") return ReachMethod::kAuto;
  throw InputError("unknown reach method '" + text + "' (spline, joint or auto)");
}

const char* ToString(SynthesisMethod method) {
  switch (method) {
    case SynthesisMethod::kInterp:
      return "interp";
    case SynthesisMethod::kLine:
      return "line";
    case SynthesisMethod::kNearest:
      return "nearest";
  }
  return "?";
}

SynthesisMethod ParseSynthesisMethod(const std::string& text) {
  if (text == "interp") return SynthesisMethod::kInterp;
  if (text == "line") return SynthesisMethod::kLine;
  if (text == "nearest") return SynthesisMethod::kNearest;
  throw InputError("unknown synthesis method '" + text + "' (interp, line or nearest)");
}

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

SynthesisModel::SynthesisModel(RobotModel robot, SceneModel scene, GraspLibrary library,
                               const LinePrincipleOptions& line_options)
    : robot_(std::move(robot)),
      scene_(std::move(scene)),
      library_(std::move(library)),
      collision_(robot_, scene_) {
  if (library_.entries.empty()) throw InputError("the grasp library has no entry");
  for (size_t i = 0; i < library_.entries.size(); ++i) {
    const LibraryEntry& e = library_.entries[i];
    std::string why;
    if (!std::isfinite(e.theta_deg)) {
      throw InputError("grasp library: entries[" + std::to_string(i) + "].theta_deg is not finite");
    }
    if (i > 0 && !(e.theta_deg > library_.entries[i - 1].theta_deg)) {
      throw InputError("grasp library: entries[" + std::to_string(i) +
                       "].theta_deg = " + Degrees(e.theta_deg) + " does not increase");
    }
    if (!IsWellFormed(e.motion, &why)) {
      throw InputError("grasp library: entries[" + std::to_string(i) + "].motion: " + why);
    }
  }
  std::string why;
  if (!line_options.IsValid(&why)) throw InputError("invalid line-principle option: " + why);
  line_ = FitLinePrinciple(library_, scene_, line_options);
  CollisionData data(collision_);
  for (const LibraryEntry& e : library_.entries) {
    RefinementInputs in;
    in.q_start = DefaultRestConfiguration(robot_, scene_, e.motion.grasp().q_WH.toRotationMatrix());
    if (line_.valid) {
      in.wrist_line = line_.wrist_line.line;
      in.handle_in_hand = line_.handle_in_hand;
    }
    entry_constraints_.push_back(EvaluateRefinementConstraints(robot_, scene_, collision_, e.motion,
                                                               in, RefinementOptions{}, &data));
  }
}

bool SynthesisOptions::IsValid(std::string* why) const {
  if (!bracket.IsValid(why) || !blend.IsValid(why) || !refinement.IsValid(why) ||
      !reach.IsValid(why) || !lift.IsValid(why) || !joint_space.IsValid(why)) {
    return false;
  }
  if (!(reach_margin >= 0.0)) {
    if (why) *why = "reach_margin must be >= 0";
    return false;
  }
  if (!joint_reach.IsValid(why)) return false;
  if (!start.allFinite() && !start.array().isNaN().all()) {
    if (why) *why = "start must be all finite or all NaN";
    return false;
  }
  return true;
}

GraspingMotion TurnWithObject(const GraspingMotion& motion, double theta) {
  GraspingMotion out = motion;
  const Eigen::AngleAxisd turn(theta - motion.theta, Eigen::Vector3d::UnitZ());
  for (MotionWaypoint& w : out.waypoints) {
    w.p_WH = motion.p_WO + turn * (w.p_WH - motion.p_WO);
    w.q_WH = (Eigen::Quaterniond(turn) * w.q_WH).normalized();
  }
  out.theta = theta;
  return out;
}

SynthesisResult SynthesizeGrasp(const SynthesisModel& model, double theta_deg,
                                const SynthesisOptions& options, CollisionData* data) {
  std::string why;
  if (!options.IsValid(&why)) throw InputError("invalid synthesis option: " + why);
  if (!std::isfinite(theta_deg)) throw InputError("theta is not finite");
  const RobotModel& robot = model.robot();
  const SceneModel& scene = model.scene();
  const GraspLibrary& library = model.library();
  const LinePrincipleModel& line = model.line();
  const double theta = theta_deg * kDeg;
  SynthesisResult r;
  r.theta_deg = theta_deg;
  r.requested = options.method;
  r.used = options.method;
  r.bracket = SelectBracket(library, scene, theta_deg, options.bracket);
  const Bracket& b = r.bracket;
  const bool has_start = options.start.allFinite();
  const ArmBranch branch = has_start ? BranchOf(options.start) : ArmBranch{};
  const double min_width = options.refinement.min_psi_width;

  // 1. the grasping motion.
  const auto t_generate = Clock::now();
  GraspingMotion motion;
  auto use_nearest = [&](int i) {
    motion = TurnWithObject(library.entries[i].motion, theta);
    r.sources = {Source(library, i, 1.0)};
  };
  auto use_line = [&](int side) {
    r.side = side;
    motion = LinePrincipleMotion(line, scene, theta, side);
    r.sources.clear();
    for (size_t i = 0; i < library.entries.size(); ++i) {
      r.sources.push_back(Source(library, static_cast<int>(i), 1.0 / library.entries.size()));
    }
  };
  switch (options.method) {
    case SynthesisMethod::kNearest:
      use_nearest(b.nearest);
      break;
    case SynthesisMethod::kLine:
      if (!line.valid) {
        r.status = SynthesisStatus::kNoModel;
        r.message = "the line principle cannot be used with this library: " + line.message;
        return r;
      }
      use_line(line.entry_sides[b.nearest]);
      break;
    case SynthesisMethod::kInterp:
      if (b.kind == BracketKind::kBelowRange || b.kind == BracketKind::kAboveRange) {
        r.status = SynthesisStatus::kOutOfRange;
        r.message = "theta " + Degrees(theta_deg) + " deg is outside the library's range [" +
                    Degrees(model.theta_min_deg()) + ", " + Degrees(model.theta_max_deg()) +
                    "] deg: interpolation needs a demonstration on each side; use method "
                    "'line' (the line principle) or 'nearest' beyond the range";
        return r;
      }
      if (b.kind == BracketKind::kExact && b.substitute >= 0) {
        // a weak representative: its robust neighbour turned with the object.
        use_nearest(b.substitute);
        r.used = SynthesisMethod::kNearest;
        r.fallback = true;
        std::ostringstream f;
        f << b.reason << "; used its robust neighbour (" << library.entries[b.substitute].theta_deg
          << " deg) turned with the object";
        r.fallback_reason = f.str();
      } else if (b.kind == BracketKind::kExact) {
        use_nearest(b.lower);
      } else if (b.blendable) {
        motion = BlendMotions(library.entries[b.lower].motion, library.entries[b.upper].motion, b.t,
                              options.blend);
        motion.theta = theta;
        r.sources = {Source(library, b.lower, 1.0 - b.t), Source(library, b.upper, b.t)};
      } else {
        // the hard case: documented fallback order (synthesis.hpp).
        r.fallback = true;
        // the robust end when exactly one is weak, else the nearer one.
        const int nearer = b.weak_lower != b.weak_upper ? (b.weak_lower ? b.upper : b.lower)
                           : b.t <= 0.5                 ? b.lower
                                                        : b.upper;
        std::ostringstream f;
        f << "the bracket " << library.entries[b.lower].theta_deg << " - "
          << library.entries[b.upper].theta_deg << " deg cannot be blended (" << b.reason << ")";
        const GraspingMotion turned = TurnWithObject(library.entries[nearer].motion, theta);
        if (Reachable(robot, turned, branch, min_width)) {
          use_nearest(nearer);
          r.used = SynthesisMethod::kNearest;
          f << "; used the " << (b.weak_lower != b.weak_upper ? "robust" : "nearer")
            << " demonstration (" << library.entries[nearer].theta_deg
            << " deg) turned with the object";
        } else {
          f << "; the nearer demonstration turned with the object is not reachable with "
            << min_width / kDeg << " deg of arm angle";
          bool done = false;
          if (line.valid) {
            const int side = line.entry_sides[nearer];
            const GraspingMotion lm = LinePrincipleMotion(line, scene, theta, side);
            if (Reachable(robot, lm, branch, min_width)) {
              use_line(side);
              r.used = SynthesisMethod::kLine;
              f << "; used the line principle on side " << side;
              done = true;
            } else {
              f << "; the line principle's grasp is not reachable either";
            }
          }
          if (!done) {
            motion = BlendMotions(library.entries[b.lower].motion, library.entries[b.upper].motion,
                                  b.t, options.blend);
            motion.theta = theta;
            r.sources = {Source(library, b.lower, 1.0 - b.t), Source(library, b.upper, b.t)};
            f << "; used the plain blend, left to the refinement";
          }
        }
        r.fallback_reason = f.str();
      }
      break;
  }
  r.unrefined = motion;
  r.generate_s = Since(t_generate);

  // 2. the start configuration.
  if (has_start) {
    for (int j = 0; j < kArmDof; ++j) {
      if (options.start[j] < robot.arm.lower()[j] || options.start[j] > robot.arm.upper()[j]) {
        r.status = SynthesisStatus::kBadStart;
        std::ostringstream s;
        s << "start configuration: joint " << j + 1 << " = " << options.start[j]
          << " rad is outside its limits [" << robot.arm.lower()[j] << ", " << robot.arm.upper()[j]
          << "]";
        r.message = s.str();
        return r;
      }
    }
    r.start = options.start;
  } else {
    r.start = DefaultRestConfiguration(robot, scene, motion.grasp().q_WH.toRotationMatrix());
  }
  SetState(model.collision(), r.start, motion.pregrasp().f, theta, data);
  CollideOptions co;
  co.max_pairs = 1;
  const CollisionReport hit =
      Collide(model.collision(), GroupSet::Robot(), GroupSet::World(), data, co);
  if (hit.collision()) {
    r.status = SynthesisStatus::kBadStart;
    r.message = "start configuration is in collision: " + hit.BriefReport();
    return r;
  }

  // 3. refinement.
  const auto t_refine = Clock::now();
  if (options.refine) {
    RefinementInputs in;
    in.q_start = r.start;
    if (line.valid) {
      in.wrist_line = line.wrist_line.line;
      in.handle_in_hand = line.handle_in_hand;
    }
    RefinementOptions ro = options.refinement;
    if (options.thresholds_from_sources) {
      std::vector<int> sources;
      if (r.used == SynthesisMethod::kLine) {
        sources.push_back(b.nearest);
      } else {
        for (const SourceDemo& s : r.sources) sources.push_back(s.entry);
      }
      for (int i : sources) {
        const RefinementConstraints& c = model.entry_constraints()[i];
        ro.clearance_margin = std::min(ro.clearance_margin, c.approach_clearance);
        ro.penetration_tolerance = std::max(ro.penetration_tolerance, -c.grasp_clearance);
        if (std::isfinite(c.contact_error)) {
          ro.contact_tolerance = std::max(ro.contact_tolerance, c.contact_error);
        }
      }
    }
    r.clearance_margin = ro.clearance_margin;
    r.penetration_tolerance = ro.penetration_tolerance;
    r.contact_tolerance = ro.contact_tolerance;
    RefinementResult rr =
        RefineGraspingMotion(robot, scene, model.collision(), motion, in, ro, data);
    motion = std::move(rr.motion);
    r.refinement = std::move(rr.report);
    r.refined = true;
  }
  r.motion = motion;
  r.refine_s = Since(t_refine);

  // 4. reach, grasping motion, lift, joints.
  const auto t_joints = Clock::now();
  // after the pre-grasp: the grasping motion and the lift, times from the pre-grasp.
  CartesianPath tail(motion.waypoints.begin(), motion.waypoints.end());
  const size_t tail_grasp = tail.size() - 1;
  LiftOptions lift = options.lift;
  double height = 0.0, duration = 0.0;
  for (const SourceDemo& s : r.sources) {
    height += s.weight * library.entries[s.entry].lift_height;
    duration += s.weight * library.entries[s.entry].lift_duration;
  }
  if (height > 0.0) lift.height = height;
  if (duration > 0.0) lift.duration = duration;
  const CartesianPath up = LiftPath(tail.back(), lift);
  tail.insert(tail.end(), up.begin(), up.end());

  const ReachAttempt spline =
      options.reach_method == ReachMethod::kJoint
          ? ReachAttempt{}
          : SplineReachAttempt(robot, motion, tail, r.start, theta_deg, options);
  std::ostringstream reach_why;
  std::optional<ReachAttempt> chosen;
  if (options.reach_method == ReachMethod::kSpline) {
    chosen = spline;
    reach_why << "spline reach requested";
    if (!spline.ok() && !has_start) {
      // the default rest pose on another branch (the wrist flip first), as ReplayDemoLog does:
      // a hand turned far from the rest orientation can need it. A start given by the user is
      // kept.
      const Eigen::Isometry3d X_rest_flange = ArmFlangePose(robot.arm, r.start);
      for (int index : {4, 1, 5, 2, 6, 3, 7}) {
        const std::optional<MidArcSolution> other =
            SolveArmIkMidArc(robot.arm, X_rest_flange, ArmBranch::FromIndex(index));
        if (!other || InCollision(model, other->q, motion.pregrasp().f, theta, data)) continue;
        ReachAttempt a = SplineReachAttempt(robot, motion, tail, other->q, theta_deg, options);
        if (a.ok()) {
          r.start = other->q;
          chosen = std::move(a);
          reach_why << "; the rest pose on branch " << index
                    << " (the elbow-up one cannot play it)";
          break;
        }
      }
    }
  } else {
    if (options.reach_method == ReachMethod::kAuto) {
      if (spline.margin_ok()) {
        chosen = spline;
        reach_why << "spline reach (reachable with " << options.reach_margin * 1000.0
                  << " mm to spare)";
      } else if (spline.ok()) {
        reach_why << "the spline reach passes within " << options.reach_margin * 1000.0
                  << " mm of the workspace's edge at wrist pose " << spline.margin_failed_sample;
      } else {
        reach_why << "the spline reach cannot be played: " << spline.joints.message;
      }
    } else {
      reach_why << "joint reach requested";
    }
    if (!chosen) {
      std::string joint_why;
      std::optional<ReachAttempt> joint = JointReachAttempt(model, motion, tail, r.start, theta,
                                                            theta_deg, options, data, &joint_why);
      if (joint) {
        chosen = std::move(joint);
        reach_why << "; joint reach" << joint_why;
      } else {
        reach_why << "; the joint reach failed too: " << joint_why;
        if (spline.ok()) {
          chosen = spline;
          reach_why << "; kept the spline reach";
        }
      }
    }
  }
  r.joints_s = Since(t_joints);
  r.reach_reason = reach_why.str();
  if (!chosen || !chosen->ok()) {
    r.status = SynthesisStatus::kUnreachable;
    r.message = "the synthesized motion cannot be played from the start configuration: " +
                (chosen ? chosen->joints.message : r.reach_reason);
    if (chosen) r.joints = chosen->joints;
    return r;
  }
  r.reach_used = chosen->method;
  r.path = std::move(chosen->path);
  r.joints = std::move(chosen->joints);
  const size_t i_pre = chosen->reach_samples - 1;
  const size_t i_grasp = i_pre + tail_grasp;
  size_t i_top = r.path.size() - 1;
  for (size_t i = i_grasp; i < r.path.size(); ++i) {
    if (r.path[i].p_WH.z() >= r.path[i_grasp].p_WH.z() + lift.height - 1e-9) {
      i_top = i;
      break;
    }
  }
  size_t i_lift = i_grasp;
  while (i_lift + 1 < r.path.size() &&
         r.path[i_lift + 1].p_WH.z() <= r.path[i_grasp].p_WH.z() + 1e-9) {
    ++i_lift;
  }
  r.trajectory = r.joints.trajectory;
  r.trajectory.samples.front().arm = r.start;
  r.trajectory.waypoints.clear();
  for (size_t i : {size_t{0}, i_pre, i_grasp, i_lift, i_top}) {
    if (!r.trajectory.waypoints.empty() &&
        r.trajectory.samples[i].t <= r.trajectory.waypoints.back().t) {
      continue;
    }
    WristWaypoint w;
    w.t = r.trajectory.samples[i].t;
    w.p_WH = r.path[i].p_WH;
    w.q_WH = r.path[i].q_WH.normalized();
    r.trajectory.waypoints.push_back(w);
  }
  r.status = SynthesisStatus::kOk;
  return r;
}

}  // namespace graspsynth
