#include "solver/synthesis.hpp"

#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "common/errors.hpp"
#include "kinematics/arm_ik.hpp"
#include "simulation/scripted_grasp.hpp"

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

}  // namespace

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
}

bool SynthesisOptions::IsValid(std::string* why) const {
  if (!bracket.IsValid(why) || !blend.IsValid(why) || !refinement.IsValid(why) ||
      !reach.IsValid(why) || !lift.IsValid(why) || !joint_space.IsValid(why)) {
    return false;
  }
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
      if (b.kind == BracketKind::kExact) {
        use_nearest(b.lower);
      } else if (b.blendable) {
        motion = BlendMotions(library.entries[b.lower].motion, library.entries[b.upper].motion, b.t,
                              options.blend);
        motion.theta = theta;
        r.sources = {Source(library, b.lower, 1.0 - b.t), Source(library, b.upper, b.t)};
      } else {
        // the hard case: documented fallback order (synthesis.hpp).
        r.fallback = true;
        const int nearer = b.t <= 0.5 ? b.lower : b.upper;
        std::ostringstream f;
        f << "the bracket " << library.entries[b.lower].theta_deg << " - "
          << library.entries[b.upper].theta_deg << " deg cannot be blended (" << b.reason << ")";
        const GraspingMotion turned = TurnWithObject(library.entries[nearer].motion, theta);
        if (Reachable(robot, turned, branch, min_width)) {
          use_nearest(nearer);
          r.used = SynthesisMethod::kNearest;
          f << "; used the nearer demonstration (" << library.entries[nearer].theta_deg
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
    RefinementResult rr =
        RefineGraspingMotion(robot, scene, model.collision(), motion, in, options.refinement, data);
    motion = std::move(rr.motion);
    r.refinement = std::move(rr.report);
    r.refined = true;
  }
  r.motion = motion;
  r.refine_s = Since(t_refine);

  // 4. reach, grasping motion, lift, joints.
  const auto t_joints = Clock::now();
  MotionWaypoint start;
  const Eigen::Isometry3d X_start = ArmFlangePose(robot.arm, r.start) * robot.X_FH;
  start.p_WH = X_start.translation();
  start.q_WH = Eigen::Quaterniond(X_start.linear()).normalized();
  start.f = motion.pregrasp().f;
  const MotionWaypoint& w0 = motion.waypoints[0];
  const MotionWaypoint& w1 = motion.waypoints[1];
  const Eigen::Vector3d v_end = (w1.p_WH - w0.p_WH) / std::max(1e-6, w1.t - w0.t);
  r.path = SplineReach(start, motion.pregrasp(), v_end, options.reach);
  const double t0 = r.path.back().t;
  const size_t i_pre = r.path.size() - 1;
  for (size_t i = 1; i < motion.waypoints.size(); ++i) {
    MotionWaypoint w = motion.waypoints[i];
    w.t += t0;
    r.path.push_back(w);
  }
  const size_t i_grasp = r.path.size() - 1;
  LiftOptions lift = options.lift;
  double height = 0.0, duration = 0.0;
  for (const SourceDemo& s : r.sources) {
    height += s.weight * library.entries[s.entry].lift_height;
    duration += s.weight * library.entries[s.entry].lift_duration;
  }
  if (height > 0.0) lift.height = height;
  if (duration > 0.0) lift.duration = duration;
  const CartesianPath up = LiftPath(r.path.back(), lift);
  r.path.insert(r.path.end(), up.begin(), up.end());
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
  r.joints = ToJointTrajectory(robot, r.path, r.start, theta_deg, options.joint_space);
  if (r.joints.status != JointSpaceStatus::kOk && !has_start) {
    // the default rest pose on another branch (the wrist flip first), as ReplayDemoLog does: a
    // hand turned far from the rest orientation can need it. A start given by the user is kept.
    const Eigen::Isometry3d X_rest_flange = ArmFlangePose(robot.arm, r.start);
    for (int index : {4, 1, 5, 2, 6, 3, 7}) {
      const std::optional<MidArcSolution> other =
          SolveArmIkMidArc(robot.arm, X_rest_flange, ArmBranch::FromIndex(index));
      if (!other) continue;
      SetState(model.collision(), other->q, motion.pregrasp().f, theta, data);
      if (Collide(model.collision(), GroupSet::Robot(), GroupSet::World(), data, co).collision()) {
        continue;
      }
      JointSpaceResult joints =
          ToJointTrajectory(robot, r.path, other->q, theta_deg, options.joint_space);
      if (joints.status == JointSpaceStatus::kOk) {
        r.start = other->q;
        r.joints = std::move(joints);
        break;
      }
    }
  }
  r.joints_s = Since(t_joints);
  if (r.joints.status != JointSpaceStatus::kOk) {
    r.status = SynthesisStatus::kUnreachable;
    r.message =
        "the synthesized motion cannot be played from the start configuration: " + r.joints.message;
    return r;
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
