#pragma once

/// @file
/// What every stage of the synthesis (synthesis.hpp) shares: the model, built once from the
/// robot, scene and library, and the task, the object's placement entered once per query.

#include <optional>
#include <string_view>
#include <vector>

#include "collision/collision_scene.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/grasp_library.hpp"
#include "scene/scene_model.hpp"
#include "solver/line_principle.hpp"
#include "solver/placement_cell.hpp"
#include "solver/refinement.hpp"

namespace graspsynth {

/// What the synthesis needs an object's handle for, in the words of the error that refuses an
/// object without one (ObjectModel::Handle).
inline constexpr std::string_view kSynthesisNeedsHandle =
    "the synthesis (its line principle and refinement aim at the handle)";

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
  /// in physics did (SynthesisOptions::source_thresholds).
  const std::vector<RefinementConstraints>& entry_constraints() const { return entry_constraints_; }
  /// The library's range, deg.
  double theta_min_deg() const { return theta_min_deg_; }
  double theta_max_deg() const { return theta_max_deg_; }
  /// Each entry's side of the handle (+1, -1; GraspSide), in entry order.
  const std::vector<int>& entry_sides() const { return entry_sides_; }

  /// True when the library holds demonstrations at several object positions
  /// (GraspLibrary::HasPositions): the synthesis then works over placements (x, y, theta),
  /// solver/placement_motion.hpp.
  bool placements() const { return triangulation_.has_value(); }
  /// The Delaunay triangulation of the entries' placements, entry order; placements() only.
  const PlacementTriangulation& triangulation() const;
  /// The entries the line principle is fitted over, by index: every entry, or for a library
  /// over placements those at the position nearest the scene's object centre (the line
  /// principle models one position's grasps as a function of theta).
  std::vector<int> LineEntries() const;

 private:
  GraspLibrary LineLibrary() const;

  RobotModel robot_;
  SceneModel scene_;
  GraspLibrary library_;
  CollisionModel collision_;
  LinePrincipleModel line_;
  std::vector<RefinementConstraints> entry_constraints_;
  double theta_min_deg_ = 0.0, theta_max_deg_ = 0.0;
  std::vector<int> entry_sides_;
  std::optional<PlacementTriangulation> triangulation_;
};

/// The synthesis's per-thread workspace (STYLE.md's Data): everything a query writes while it
/// runs, made from a SynthesisModel and reused from one query to the next; one per thread. It
/// holds the collision data every stage moves the robot and the object in. The stages' other
/// working state (the Ceres problem, whose residuals hold the motion; NLopt's optimizer, set up
/// from the options; the IK, which keeps no scratch) is built per query: reusing it would not
/// save a measurable share of a query, and the results must not depend on what ran before.
class SynthesisData {
 public:
  /// A workspace for queries on `model`, which must outlive it.
  explicit SynthesisData(const SynthesisModel& model) : collision_(model.collision()) {}

  /// The collision data, made from model.collision().
  CollisionData* collision() { return &collision_; }

 private:
  CollisionData collision_;
};

/// One synthesis query: the object's placement, converted from the degrees the user gives
/// once, and the object's pose computed from it once; every stage reads it from here.
struct SynthesisTask {
  double theta_deg = 0.0;  ///< the object orientation as asked, deg (bracket, reports)
  Placement placement;     ///< the object's placement, theta = theta_deg * pi / 180 rad
  /// The object's pose at rest, scene.ObjectPose(placement) (object frame O in world W).
  Eigen::Isometry3d X_WO = Eigen::Isometry3d::Identity();
};

/// The task of orientation `theta_deg` (deg) in `scene`, the object at `at` (its centre on the
/// table, world, m) or, without it, at the scene's object centre. Throws InputError when theta
/// is not finite or `at` is not on the table.
SynthesisTask MakeSynthesisTask(const SceneModel& scene, double theta_deg,
                                const std::optional<Eigen::Vector2d>& at = {});

/// A placement as the placement space's coordinates (x, y, theta): m, m, rad.
Eigen::Vector3d PlacementCoordinates(const SceneModel& scene, const Placement& placement);

}  // namespace graspsynth
