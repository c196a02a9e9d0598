#include "solver/placement_motion.hpp"

#include <algorithm>
#include <sstream>
#include <vector>

#include "kinematics/pose_math.hpp"

namespace graspsynth {
namespace {

std::string PlacementText(const Eigen::Vector3d& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << " m, " << p.z() / kDeg << " deg)";
  return s.str();
}

SourceDemo Source(const GraspLibrary& library, int i, double weight) {
  const LibraryEntry& e = library.entries[static_cast<size_t>(i)];
  return {i, e.theta_deg, e.file, e.trial, weight};
}

// Entry i moved and turned with the object to the task's placement.
void UseVertex(const SynthesisModel& model, const SynthesisTask& task, int i,
               MotionGenerationResult* r) {
  const LibraryEntry& e = model.library().entries[static_cast<size_t>(i)];
  const Placement to{task.placement.theta, model.scene().CentreXY(task.placement)};
  const Placement from = e.placement();
  r->motion =
      from.theta == to.theta && *from.xy == *to.xy ? e.motion : TurnWithObject(e.motion, to);
  r->sources = {Source(model.library(), i, 1.0)};
}

// The weighted blend of the cell's vertices, moved to the task's placement.
void UseCellBlend(const SynthesisModel& model, const SynthesisTask& task, const PlacementCell& cell,
                  const MotionGenerationOptions& options, MotionGenerationResult* r) {
  if (cell.vertices.size() == 1) {
    UseVertex(model, task, cell.vertices.front(), r);
    return;
  }
  std::vector<const GraspingMotion*> motions;
  r->sources.clear();
  for (size_t k = 0; k < cell.vertices.size(); ++k) {
    motions.push_back(&model.library().entries[static_cast<size_t>(cell.vertices[k])].motion);
    r->sources.push_back(Source(model.library(), cell.vertices[k], cell.weights[k]));
  }
  const GraspingMotion blend = BlendMotionsWeighted(motions, cell.weights, options.blend);
  // the barycentric weights reproduce the query's placement up to rounding: move the rest.
  r->motion = TurnWithObject(
      blend, Placement{task.placement.theta, model.scene().CentreXY(task.placement)});
}

// Why the cell's grasps cannot be blended ("" when they can), as a bracket's (bracket.hpp).
std::string CellReason(const SynthesisModel& model, const PlacementCell& cell,
                       const BracketOptions& options) {
  const GraspLibrary& library = model.library();
  std::ostringstream why;
  auto add = [&why](const std::string& text) {
    if (why.tellp() > 0) why << "; ";
    why << text;
  };
  bool sides_differ = false, weak = false, robust = false;
  double change = 0.0;
  for (size_t a = 0; a < cell.vertices.size(); ++a) {
    const LibraryEntry& ea = library.entries[static_cast<size_t>(cell.vertices[a])];
    (ea.score < options.min_score ? weak : robust) = true;
    const Eigen::Quaterniond R_OH_a =
        Eigen::Quaterniond(model.scene().ObjectPose(ea.placement()).linear()).conjugate() *
        ea.motion.grasp().q_WH;
    for (size_t b = a + 1; b < cell.vertices.size(); ++b) {
      const LibraryEntry& eb = library.entries[static_cast<size_t>(cell.vertices[b])];
      const Eigen::Quaterniond R_OH_b =
          Eigen::Quaterniond(model.scene().ObjectPose(eb.placement()).linear()).conjugate() *
          eb.motion.grasp().q_WH;
      change = std::max(change, AngleBetween(R_OH_a, R_OH_b));
      sides_differ |= model.entry_sides()[static_cast<size_t>(cell.vertices[a])] !=
                      model.entry_sides()[static_cast<size_t>(cell.vertices[b])];
    }
  }
  if (sides_differ) add("the wrist is on different sides of the handle at its vertices");
  if (change > options.max_orientation_change) {
    std::ostringstream s;
    s << "the grasp orientations relative to the object differ by up to " << change / kDeg
      << " deg (more than " << options.max_orientation_change / kDeg << ")";
    add(s.str());
  }
  if (weak && robust) {
    std::ostringstream s;
    s << "a vertex is weak (robustness score below " << options.min_score << ")";
    add(s.str());
  }
  return why.str();
}

std::string CellText(const SynthesisModel& model, const PlacementCell& cell) {
  std::ostringstream s;
  s << "{";
  for (size_t k = 0; k < cell.vertices.size(); ++k) {
    s << (k ? ", " : "")
      << PlacementText(model.triangulation().placements()[static_cast<size_t>(cell.vertices[k])])
      << " w " << cell.weights[k];
  }
  s << "}";
  return s.str();
}

// The heaviest vertex that is not weak (the heaviest of all when every one is).
int HeaviestRobust(const SynthesisModel& model, const PlacementCell& cell, double min_score) {
  int best = -1;
  for (int pass = 0; pass < 2 && best < 0; ++pass) {
    double w = -1.0;
    for (size_t k = 0; k < cell.vertices.size(); ++k) {
      const int v = cell.vertices[k];
      if (pass == 0 && model.library().entries[static_cast<size_t>(v)].score < min_score) continue;
      if (cell.weights[k] > w) {
        w = cell.weights[k];
        best = v;
      }
    }
  }
  return best;
}

// The cell's vertex `anchor` (its heaviest robust one, HeaviestRobust) and every other vertex
// with weight that can be blended with those kept before it, heaviest first, the weights scaled
// to sum to one; fewer than two vertices, or all of them (the cell itself, which cannot be
// blended), give an empty cell.
PlacementCell BlendableSubcell(const SynthesisModel& model, const PlacementCell& cell, int anchor,
                               const BracketOptions& options) {
  // the anchor first (a single vertex can always be blended), then the others heaviest first
  std::vector<size_t> order(cell.vertices.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return (cell.vertices[a] == anchor) != (cell.vertices[b] == anchor)
               ? cell.vertices[a] == anchor
               : cell.weights[a] > cell.weights[b];
  });
  PlacementCell sub = cell;
  sub.vertices.clear();
  sub.weights.clear();
  for (size_t k : order) {
    sub.vertices.push_back(cell.vertices[k]);
    sub.weights.push_back(cell.weights[k]);
    if (!CellReason(model, sub, options).empty()) {
      sub.vertices.pop_back();
      sub.weights.pop_back();
    }
  }
  if (sub.vertices.size() < 2 || sub.vertices.size() == cell.vertices.size()) return {};
  double total = 0.0;
  for (double w : sub.weights) total += w;
  for (double& w : sub.weights) w /= total;
  return sub;
}

void GenerateCellInterp(const SynthesisModel& model, const SynthesisTask& task,
                        const Eigen::Vector3d& query, const MotionGenerationOptions& options,
                        MotionGenerationResult* r) {
  const PlacementCell cell = model.triangulation().Locate(query);
  if (!cell.inside) {
    r->status = MotionGenerationStatus::kOutOfRange;
    r->message = cell.reason +
                 ": interpolation needs the placement inside the demonstrated ones; use method "
                 "'nearest' or 'line' beyond them";
    return;
  }
  Bracket& b = r->bracket;
  b.kind = cell.vertices.size() == 1 ? BracketKind::kExact : BracketKind::kInside;
  std::string why = cell.vertices.size() == 1 ? "" : CellReason(model, cell, options.bracket);
  if (why.empty() && options.reject_blend) {
    why = "its blend failed its nominal trial in physics";
    r->fallback.blend_failed = true;
  }
  b.blendable = why.empty();
  b.reason = why;
  if (why.empty()) {
    UseCellBlend(model, task, cell, options, r);
    return;
  }
  FallbackReason& f = r->fallback;
  f.bracket_reason = why;
  f.cell = CellText(model, cell);
  const int vertex = HeaviestRobust(model, cell, options.bracket.min_score);
  const PlacementCell sub = options.reject_blend
                                ? PlacementCell{}
                                : BlendableSubcell(model, cell, vertex, options.bracket);
  if (!sub.vertices.empty()) {
    MotionGenerationResult partial;
    UseCellBlend(model, task, sub, options, &partial);
    if (Reachable(model.robot(), partial.motion, options.branch, options.min_psi_width)) {
      r->motion = std::move(partial.motion);
      r->sources = std::move(partial.sources);
      f.kind = FallbackKind::kPartialBlend;
      f.used_placement = CellText(model, sub);
      return;
    }
  }
  MotionGenerationResult turned;
  UseVertex(model, task, vertex, &turned);
  if (Reachable(model.robot(), turned.motion, options.branch, options.min_psi_width)) {
    r->motion = std::move(turned.motion);
    r->sources = std::move(turned.sources);
    r->used = SynthesisMethod::kNearest;
    f.kind = FallbackKind::kTurnedDemo;
    f.used_deg = model.library().entries[static_cast<size_t>(vertex)].theta_deg;
    f.used_placement =
        PlacementText(model.triangulation().placements()[static_cast<size_t>(vertex)]);
    return;
  }
  f.min_psi_width = options.min_psi_width;
  UseCellBlend(model, task, cell, options, r);
  f.kind = FallbackKind::kPlainBlend;
}

}  // namespace

MotionGenerationResult GeneratePlacementMotion(const SynthesisModel& model,
                                               const SynthesisTask& task,
                                               const MotionGenerationOptions& options) {
  MotionGenerationResult r;
  r.used = options.method;
  const Eigen::Vector3d query = PlacementCoordinates(model.scene(), task.placement);
  const int nearest = model.triangulation().Nearest(query);
  r.bracket.nearest = nearest;
  r.bracket.lower = r.bracket.upper = nearest;
  r.bracket.kind = BracketKind::kExact;
  switch (options.method) {
    case SynthesisMethod::kNearest:
      UseVertex(model, task, nearest, &r);
      break;
    case SynthesisMethod::kLine: {
      const LinePrincipleModel& line = model.line();
      if (!line.valid) {
        r.status = MotionGenerationStatus::kNoModel;
        r.message = "the line principle cannot be used with this library: " + line.message;
        return r;
      }
      r.side = model.entry_sides()[static_cast<size_t>(nearest)];
      r.motion = LinePrincipleMotion(line, task.placement, task.X_WO, r.side);
      const std::vector<int> fitted = model.LineEntries();
      for (int i : fitted) {
        r.sources.push_back(Source(model.library(), i, 1.0 / static_cast<double>(fitted.size())));
      }
      break;
    }
    case SynthesisMethod::kInterp:
      r.bracket.lower = r.bracket.upper = -1;
      GenerateCellInterp(model, task, query, options, &r);
      break;
  }
  return r;
}

}  // namespace graspsynth
