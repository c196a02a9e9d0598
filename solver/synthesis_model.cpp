#include "solver/synthesis_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/demand.hpp"
#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"
#include "motion/scripted_grasp.hpp"
#include "scene/base_frame.hpp"

namespace graspsynth {

SynthesisTask MakeSynthesisTask(const SceneModel& scene, double theta_deg,
                                const std::optional<Eigen::Vector2d>& at) {
  if (!std::isfinite(theta_deg)) throw InputError("theta is not finite");
  SynthesisTask task;
  task.theta_deg = theta_deg;
  task.placement.theta = theta_deg * kDeg;
  if (at) {
    // --at is in the study's world; the model's scene in the robot's base frame.
    const Eigen::Vector2d xy = TablePointInScene(scene, *at);
    scene.CheckOnTable(xy);
    task.placement.xy = xy;
  }
  task.X_WO = scene.ObjectPose(task.placement);
  return task;
}

Eigen::Vector3d PlacementCoordinates(const SceneModel& scene, const Placement& placement) {
  const Eigen::Vector2d xy = scene.CentreXY(placement);
  return {xy.x(), xy.y(), placement.theta};
}

SynthesisModel::SynthesisModel(RobotModel robot, SceneModel scene, GraspLibrary library,
                               const LinePrincipleOptions& line_options)
    : robot_(std::move(robot)),
      scene_(SceneInBaseFrame(std::move(scene), robot_.X_WB)),
      library_(std::move(library)),
      collision_(robot_, scene_) {
  // the file's checks (ReadGraspLibrary) again, for a library built in memory.
  const std::string where =
      library_.source.empty() ? std::string("grasp library") : library_.source;
  if (library_.entries.empty()) {
    throw InputError(where +
                     ": entries: the grasp library has no entry (its selection found no "
                     "orientation with a successful demonstration); nothing to synthesize from");
  }
  const bool positions = library_.HasPositions();
  for (size_t i = 0; i < library_.entries.size(); ++i) {
    const LibraryEntry& e = library_.entries[i];
    const std::string field = where + ": entries[" + std::to_string(i) + "]";
    std::string why;
    if (!std::isfinite(e.theta_deg)) throw InputError(field + ".theta_deg is not finite");
    if (!e.motion.p_WO.allFinite())
      throw InputError(field + ".motion.object_position is not finite");
    if (positions && i > 0) {
      const LibraryEntry& b = library_.entries[i - 1];
      if (!PlacementBefore(b.motion.p_WO.head<2>(), b.theta_deg, e.motion.p_WO.head<2>(),
                           e.theta_deg)) {
        throw InputError(field +
                         ": its placement does not come after the previous entry's (x, "
                         "then y, then theta)");
      }
    } else if (i > 0 && !(e.theta_deg > library_.entries[i - 1].theta_deg)) {
      throw InputError(field + ".theta_deg = " + StreamNumber(e.theta_deg) + " does not increase");
    }
    if (!IsWellFormed(e.motion, &why)) throw InputError(field + ".motion: " + why);
    theta_min_deg_ = i == 0 ? e.theta_deg : std::min(theta_min_deg_, e.theta_deg);
    theta_max_deg_ = i == 0 ? e.theta_deg : std::max(theta_max_deg_, e.theta_deg);
  }
  RequireValid(line_options, "invalid line-principle option");
  if (positions) {
    std::vector<Eigen::Vector3d> placements;
    for (const LibraryEntry& e : library_.entries) {
      placements.push_back(PlacementCoordinates(scene_, e.placement()));
      entry_sides_.push_back(GraspSide(scene_, e, line_options.side_dead_band));
    }
    triangulation_.emplace(placements, kDefaultThetaLength, where);
    line_ = FitLinePrinciple(LineLibrary(), scene_, line_options);
  } else {
    line_ = FitLinePrinciple(library_, scene_, line_options);
    entry_sides_ = line_.entry_sides;
  }
  CollisionData data(collision_);
  for (const LibraryEntry& e : library_.entries) {
    RefinementInputs in;
    in.X_WO = positions ? scene_.ObjectPose(e.placement()) : scene_.ObjectPose(e.motion.theta);
    in.q_start = DefaultRestConfiguration(robot_, scene_, e.motion.grasp().q_WH.toRotationMatrix());
    if (line_.valid) {
      in.wrist_line = line_.wrist_line.line;
      in.handle_in_hand = line_.handle_in_hand;
    }
    entry_constraints_.push_back(EvaluateRefinementConstraints(robot_, scene_, collision_, e.motion,
                                                               in, RefinementOptions{}, &data));
  }
}

const PlacementTriangulation& SynthesisModel::triangulation() const {
  GS_DEMAND(triangulation_.has_value(), "the library is of one position");
  return *triangulation_;
}

std::vector<int> SynthesisModel::LineEntries() const {
  std::vector<int> out;
  if (!placements()) {
    for (size_t i = 0; i < library_.entries.size(); ++i) out.push_back(static_cast<int>(i));
    return out;
  }
  // the position nearest the scene's object centre (the first in the library's order on ties).
  Eigen::Vector2d best = library_.entries.front().motion.p_WO.head<2>();
  for (const LibraryEntry& e : library_.entries) {
    const Eigen::Vector2d xy = e.motion.p_WO.head<2>();
    if ((xy - scene_.object_centre_xy).norm() < (best - scene_.object_centre_xy).norm() - 1e-12) {
      best = xy;
    }
  }
  for (size_t i = 0; i < library_.entries.size(); ++i) {
    if ((library_.entries[i].motion.p_WO.head<2>() - best).norm() <= 1e-9) {
      out.push_back(static_cast<int>(i));
    }
  }
  return out;
}

GraspLibrary SynthesisModel::LineLibrary() const {
  GraspLibrary sub = library_;
  sub.entries.clear();
  for (int i : LineEntries()) sub.entries.push_back(library_.entries[static_cast<size_t>(i)]);
  return sub;
}

}  // namespace graspsynth
