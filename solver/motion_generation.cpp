#include "solver/motion_generation.hpp"

#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "motion/joint_space.hpp"
#include "solver/placement_motion.hpp"

namespace graspsynth {

namespace {

SourceDemo Source(const GraspLibrary& library, int i, double weight) {
  const LibraryEntry& e = library.entries[i];
  return {i, e.theta_deg, e.file, e.trial, weight};
}

// Entry i turned with the object.
void UseNearest(const SynthesisModel& model, const SynthesisTask& task, int i,
                MotionGenerationResult* r) {
  r->motion = TurnWithObject(model.library().entries[i].motion, task.placement);
  r->sources = {Source(model.library(), i, 1.0)};
}

// The line principle on `side`, every entry a source.
void UseLine(const SynthesisModel& model, const SynthesisTask& task, int side,
             MotionGenerationResult* r) {
  const GraspLibrary& library = model.library();
  r->side = side;
  r->motion = LinePrincipleMotion(model.line(), task.placement, task.X_WO, side);
  r->sources.clear();
  for (size_t i = 0; i < library.entries.size(); ++i) {
    r->sources.push_back(Source(library, static_cast<int>(i), 1.0 / library.entries.size()));
  }
}

// The paper's blend of the bracket.
void UseBlend(const SynthesisModel& model, const SynthesisTask& task,
              const MotionGenerationOptions& options, MotionGenerationResult* r) {
  const GraspLibrary& library = model.library();
  const Bracket& b = r->bracket;
  r->motion = BlendMotions(library.entries[b.lower].motion, library.entries[b.upper].motion, b.t,
                           options.blend);
  r->motion.theta = task.placement.theta;
  // the library's object position, moved to the task's (the blend is of one position).
  if (task.placement.xy) r->motion = TurnWithObject(r->motion, task.placement);
  r->sources = {Source(library, b.lower, 1.0 - b.t), Source(library, b.upper, b.t)};
}

// The hard case (a bracket that cannot be blended): the documented fallback order.
// `why`: why the bracket cannot be blended.
void UseFallback(const SynthesisModel& model, const SynthesisTask& task,
                 const MotionGenerationOptions& options, const std::string& why,
                 MotionGenerationResult* r) {
  const GraspLibrary& library = model.library();
  const LinePrincipleModel& line = model.line();
  const Bracket& b = r->bracket;
  FallbackReason& f = r->fallback;
  f.bracket_reason = why;
  f.lower_deg = library.entries[b.lower].theta_deg;
  f.upper_deg = library.entries[b.upper].theta_deg;
  // the robust end when exactly one is weak, else the nearer one.
  f.robust = b.weak_lower != b.weak_upper;
  const int nearer = f.robust ? (b.weak_lower ? b.upper : b.lower) : b.t <= 0.5 ? b.lower : b.upper;
  const GraspingMotion turned = TurnWithObject(library.entries[nearer].motion, task.placement);
  if (Reachable(model.robot(), turned, options.branch, options.min_psi_width)) {
    UseNearest(model, task, nearer, r);
    r->used = SynthesisMethod::kNearest;
    f.kind = FallbackKind::kTurnedDemo;
    f.used_deg = library.entries[nearer].theta_deg;
    return;
  }
  f.min_psi_width = options.min_psi_width;
  if (line.valid) {
    const int side = line.entry_sides[nearer];
    const GraspingMotion lm = LinePrincipleMotion(line, task.placement, task.X_WO, side);
    if (Reachable(model.robot(), lm, options.branch, options.min_psi_width)) {
      UseLine(model, task, side, r);
      r->used = SynthesisMethod::kLine;
      f.kind = FallbackKind::kLinePrinciple;
      f.side = side;
      return;
    }
    f.line_unreachable = true;
  }
  UseBlend(model, task, options, r);
  f.kind = FallbackKind::kPlainBlend;
}

// The interp method: exact, blend, or a fallback.
void GenerateInterp(const SynthesisModel& model, const SynthesisTask& task,
                    const MotionGenerationOptions& options, MotionGenerationResult* r) {
  const Bracket& b = r->bracket;
  if (b.kind == BracketKind::kBelowRange || b.kind == BracketKind::kAboveRange) {
    r->status = MotionGenerationStatus::kOutOfRange;
    r->message = "theta " + StreamNumber(task.theta_deg) + " deg is outside the library's range [" +
                 StreamNumber(model.theta_min_deg()) + ", " + StreamNumber(model.theta_max_deg()) +
                 "] deg: interpolation needs a demonstration on each side; use method "
                 "'line' (the line principle) or 'nearest' beyond the range";
    return;
  }
  if (b.kind == BracketKind::kExact && b.substitute >= 0) {
    // a weak representative: its robust neighbour turned with the object.
    UseNearest(model, task, b.substitute, r);
    r->used = SynthesisMethod::kNearest;
    r->fallback.kind = FallbackKind::kRobustNeighbour;
    r->fallback.bracket_reason = b.reason;
    r->fallback.used_deg = model.library().entries[b.substitute].theta_deg;
  } else if (b.kind == BracketKind::kExact) {
    UseNearest(model, task, b.lower, r);
  } else if (b.blendable && !options.reject_blend) {
    UseBlend(model, task, options, r);
  } else if (b.blendable) {
    r->fallback.blend_failed = true;
    UseFallback(model, task, options, "its blend failed its nominal trial in physics", r);
  } else {
    UseFallback(model, task, options, b.reason, r);
  }
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

const char* ToString(FallbackKind kind) {
  switch (kind) {
    case FallbackKind::kNone:
      return "none";
    case FallbackKind::kRobustNeighbour:
      return "robust_neighbour";
    case FallbackKind::kTurnedDemo:
      return "turned_demo";
    case FallbackKind::kLinePrinciple:
      return "line_principle";
    case FallbackKind::kPlainBlend:
      return "plain_blend";
    case FallbackKind::kPartialBlend:
      return "partial_blend";
  }
  return "?";
}

SynthesisMethod ParseSynthesisMethod(const std::string& text) {
  if (text == "interp") return SynthesisMethod::kInterp;
  if (text == "line") return SynthesisMethod::kLine;
  if (text == "nearest") return SynthesisMethod::kNearest;
  throw InputError("unknown synthesis method '" + text + "' (interp, line or nearest)");
}

std::string FallbackReason::Text() const {
  std::ostringstream f;
  switch (kind) {
    case FallbackKind::kNone:
      return "";
    case FallbackKind::kRobustNeighbour:
      f << bracket_reason << "; used its robust neighbour (" << used_deg
        << " deg) turned with the object";
      return f.str();
    default:
      break;
  }
  if (!cell.empty()) {
    f << "the cell " << cell << " cannot be blended (" << bracket_reason << ")";
    if (kind == FallbackKind::kTurnedDemo) {
      f << "; used its heaviest robust vertex " << used_placement
        << " moved and turned with the object";
    } else if (kind == FallbackKind::kPartialBlend) {
      f << "; blended the vertices that can be, " << used_placement
        << ", moved and turned with the object";
    } else {
      f << "; no robust vertex moved with the object is reachable with " << min_psi_width / kDeg
        << " deg of arm angle; used the plain blend, left to the refinement";
    }
    return f.str();
  }
  f << "the bracket " << lower_deg << " - " << upper_deg << " deg cannot be blended ("
    << bracket_reason << ")";
  if (kind == FallbackKind::kTurnedDemo) {
    f << "; used the " << (robust ? "robust" : "nearer") << " demonstration (" << used_deg
      << " deg) turned with the object";
    return f.str();
  }
  f << "; the nearer demonstration turned with the object is not reachable with "
    << min_psi_width / kDeg << " deg of arm angle";
  if (kind == FallbackKind::kLinePrinciple) {
    f << "; used the line principle on side " << side;
    return f.str();
  }
  if (line_unreachable) f << "; the line principle's grasp is not reachable either";
  f << "; used the plain blend, left to the refinement";
  return f.str();
}

bool MotionGenerationOptions::IsValid(std::string* why) const {
  return bracket.IsValid(why) && blend.IsValid(why);
}

GraspingMotion TurnWithObject(const GraspingMotion& motion, const Placement& placement) {
  GraspingMotion out = motion;
  const Eigen::AngleAxisd turn(placement.theta - motion.theta, Eigen::Vector3d::UnitZ());
  if (placement.xy) out.p_WO.head<2>() = *placement.xy;
  for (MotionWaypoint& w : out.waypoints) {
    w.p_WH = out.p_WO + turn * (w.p_WH - motion.p_WO);
    w.q_WH = (Eigen::Quaterniond(turn) * w.q_WH).normalized();
  }
  out.theta = placement.theta;
  return out;
}

bool Reachable(const RobotModel& robot, const GraspingMotion& motion, ArmBranch branch,
               double min_width) {
  return WidestArmAngleWidth(robot, WaypointPose(motion.pregrasp()), branch) >= min_width &&
         WidestArmAngleWidth(robot, WaypointPose(motion.grasp()), branch) >= min_width;
}

MotionGenerationResult GenerateGraspingMotion(const SynthesisModel& model,
                                              const SynthesisTask& task,
                                              const MotionGenerationOptions& options) {
  if (model.placements()) return GeneratePlacementMotion(model, task, options);
  MotionGenerationResult r;
  r.used = options.method;
  r.bracket = SelectBracket(model.library(), model.scene(), task.theta_deg, options.bracket);
  switch (options.method) {
    case SynthesisMethod::kNearest:
      UseNearest(model, task, r.bracket.nearest, &r);
      break;
    case SynthesisMethod::kLine:
      if (!model.line().valid) {
        r.status = MotionGenerationStatus::kNoModel;
        r.message = "the line principle cannot be used with this library: " + model.line().message;
        return r;
      }
      UseLine(model, task, model.line().entry_sides[r.bracket.nearest], &r);
      break;
    case SynthesisMethod::kInterp:
      GenerateInterp(model, task, options, &r);
      break;
  }
  return r;
}

}  // namespace graspsynth
