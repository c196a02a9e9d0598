#include "solver/bracket.hpp"

#include <cmath>
#include <sstream>

#include "kinematics/pose_math.hpp"

namespace graspsynth {

bool BracketOptions::IsValid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(std::isfinite(max_orientation_change) && max_orientation_change > 0.0)) {
    return fail("max_orientation_change must be positive (rad)");
  }
  if (!(std::isfinite(side_dead_band) && side_dead_band >= 0.0)) {
    return fail("side_dead_band must be >= 0 (m)");
  }
  if (!(std::isfinite(min_score) && min_score >= 0.0 && min_score <= 1.0)) {
    return fail("min_score must be in [0, 1]");
  }
  if (!(std::isfinite(exact_tolerance) && exact_tolerance >= 0.0)) {
    return fail("exact_tolerance must be >= 0 (deg)");
  }
  return true;
}

const char* ToString(BracketKind kind) {
  switch (kind) {
    case BracketKind::kExact:
      return "exact";
    case BracketKind::kInside:
      return "inside";
    case BracketKind::kBelowRange:
      return "below_range";
    case BracketKind::kAboveRange:
      return "above_range";
    case BracketKind::kEmpty:
      return "empty";
  }
  return "?";
}

int HandleSide(const SceneModel& scene, double theta, const Eigen::Vector3d& p_WH,
               double dead_band) {
  return HandleSide(scene, Placement{theta, {}}, p_WH, dead_band);
}

int HandleSide(const SceneModel& scene, const Placement& placement, const Eigen::Vector3d& p_WH,
               double dead_band) {
  const Eigen::Isometry3d X_WO = scene.ObjectPose(placement);
  const Eigen::Vector3d h = scene.object.HandleDirection(X_WO);
  const Eigen::Vector3d right = h.cross(Eigen::Vector3d::UnitZ()).normalized();
  const double lateral = right.dot(p_WH - X_WO.translation());
  if (std::abs(lateral) <= dead_band) return 0;
  return lateral > 0.0 ? 1 : -1;
}

namespace {

std::string WeakReason(const LibraryEntry& w, const BracketOptions& options) {
  std::ostringstream s;
  s << "the " << w.theta_deg << " deg representative is weak (robustness score " << w.score << " < "
    << options.min_score << ")";
  return s.str();
}

// kExact on entry b->nearest: its weakness, and the robust neighbour to use in its place.
void ExactBracket(const GraspLibrary& library, double theta_deg, const BracketOptions& options,
                  Bracket* b) {
  const auto& e = library.entries;
  const int n = static_cast<int>(e.size());
  const auto weak = [&](int i) { return e[i].score < options.min_score; };
  b->kind = BracketKind::kExact;
  b->lower = b->upper = b->nearest;
  b->weak_lower = b->weak_upper = weak(b->nearest);
  if (!b->weak_lower) return;
  for (int i : {b->nearest - 1, b->nearest + 1}) {
    if (i < 0 || i >= n || weak(i)) continue;
    if (b->substitute < 0 ||
        std::abs(e[i].theta_deg - theta_deg) < std::abs(e[b->substitute].theta_deg - theta_deg)) {
      b->substitute = i;
    }
  }
  if (b->substitute >= 0) b->reason = WeakReason(e[b->nearest], options);
}

// kInside between b->lower and b->upper: blend parameter, sides, orientation change, and
// whether the two grasps can be blended.
void InsideBracket(const GraspLibrary& library, const SceneModel& scene, double theta_deg,
                   const BracketOptions& options, Bracket* b) {
  const LibraryEntry& a = library.entries[b->lower];
  const LibraryEntry& c = library.entries[b->upper];
  b->weak_lower = a.score < options.min_score;
  b->weak_upper = c.score < options.min_score;
  b->t = (theta_deg - a.theta_deg) / (c.theta_deg - a.theta_deg);
  // grasp orientations relative to the object: the same hold gives the same R_OH.
  const Eigen::Quaterniond R_OH_a =
      Eigen::Quaterniond(scene.ObjectPose(a.theta_deg * kDeg).linear()).conjugate() *
      a.motion.grasp().q_WH;
  const Eigen::Quaterniond R_OH_c =
      Eigen::Quaterniond(scene.ObjectPose(c.theta_deg * kDeg).linear()).conjugate() *
      c.motion.grasp().q_WH;
  b->orientation_change = AngleBetween(R_OH_a, R_OH_c);
  b->side_lower =
      HandleSide(scene, a.theta_deg * kDeg, a.motion.grasp().p_WH, options.side_dead_band);
  b->side_upper =
      HandleSide(scene, c.theta_deg * kDeg, c.motion.grasp().p_WH, options.side_dead_band);
  std::ostringstream why;
  if (b->side_lower != 0 && b->side_upper != 0 && b->side_lower != b->side_upper) {
    b->blendable = false;
    why << "the wrist changes sides of the handle between " << a.theta_deg << " and " << c.theta_deg
        << " deg";
  }
  if (b->orientation_change > options.max_orientation_change) {
    if (!b->blendable) why << "; ";
    b->blendable = false;
    why << "the grasp orientations relative to the object differ by "
        << b->orientation_change / kDeg << " deg (more than "
        << options.max_orientation_change / kDeg << ")";
  }
  if (b->weak_lower != b->weak_upper) {
    if (!b->blendable) why << "; ";
    b->blendable = false;
    why << WeakReason(b->weak_lower ? a : c, options);
  }
  b->reason = why.str();
}

}  // namespace

Bracket SelectBracket(const GraspLibrary& library, const SceneModel& scene, double theta_deg,
                      const BracketOptions& options) {
  Bracket b;
  const auto& e = library.entries;
  const int n = static_cast<int>(e.size());
  if (n == 0) {
    b.reason = "the library has no entry";
    return b;
  }
  // nearest entry (ties: the lower one).
  b.nearest = 0;
  for (int i = 1; i < n; ++i) {
    if (std::abs(e[i].theta_deg - theta_deg) < std::abs(e[b.nearest].theta_deg - theta_deg)) {
      b.nearest = i;
    }
  }
  if (std::abs(e[b.nearest].theta_deg - theta_deg) <= options.exact_tolerance) {
    ExactBracket(library, theta_deg, options, &b);
    return b;
  }
  if (theta_deg < e.front().theta_deg) {
    b.kind = BracketKind::kBelowRange;
    b.lower = b.upper = 0;
    return b;
  }
  if (theta_deg > e.back().theta_deg) {
    b.kind = BracketKind::kAboveRange;
    b.lower = b.upper = n - 1;
    return b;
  }
  b.kind = BracketKind::kInside;
  int i = 0;
  while (i + 1 < n && e[i + 1].theta_deg < theta_deg) ++i;
  b.lower = i;
  b.upper = i + 1;
  InsideBracket(library, scene, theta_deg, options, &b);
  return b;
}

}  // namespace graspsynth
