#include "solver/synthesis_model.hpp"

#include <sstream>

#include "common/errors.hpp"
#include "simulation/scripted_grasp.hpp"

namespace graspsynth {

namespace {

std::string Degrees(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

SynthesisTask MakeSynthesisTask(const SceneModel& scene, double theta_deg) {
  SynthesisTask task;
  task.theta_deg = theta_deg;
  task.placement.theta = theta_deg * kDeg;
  task.X_WO = scene.ObjectPose(task.placement);
  return task;
}

SynthesisModel::SynthesisModel(RobotModel robot, SceneModel scene, GraspLibrary library,
                               const LinePrincipleOptions& line_options)
    : robot_(std::move(robot)),
      scene_(std::move(scene)),
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
  for (size_t i = 0; i < library_.entries.size(); ++i) {
    const LibraryEntry& e = library_.entries[i];
    const std::string field = where + ": entries[" + std::to_string(i) + "]";
    std::string why;
    if (!std::isfinite(e.theta_deg)) throw InputError(field + ".theta_deg is not finite");
    if (i > 0 && !(e.theta_deg > library_.entries[i - 1].theta_deg)) {
      throw InputError(field + ".theta_deg = " + Degrees(e.theta_deg) + " does not increase");
    }
    if (!IsWellFormed(e.motion, &why)) throw InputError(field + ".motion: " + why);
  }
  std::string why;
  if (!line_options.IsValid(&why)) throw InputError("invalid line-principle option: " + why);
  line_ = FitLinePrinciple(library_, scene_, line_options);
  CollisionData data(collision_);
  for (const LibraryEntry& e : library_.entries) {
    RefinementInputs in;
    in.X_WO = scene_.ObjectPose(e.motion.theta);
    in.q_start = DefaultRestConfiguration(robot_, scene_, e.motion.grasp().q_WH.toRotationMatrix());
    if (line_.valid) {
      in.wrist_line = line_.wrist_line.line;
      in.handle_in_hand = line_.handle_in_hand;
    }
    entry_constraints_.push_back(EvaluateRefinementConstraints(robot_, scene_, collision_, e.motion,
                                                               in, RefinementOptions{}, &data));
  }
}

}  // namespace graspsynth
