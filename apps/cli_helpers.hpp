#pragma once

/// @file
/// Pieces shared by the commands: a list of orientations from the command line
/// (ParseOrientationList, common/orientation_list.hpp), the scene and object flags, the physics
/// perturbation's flags, and a progress bar on stderr.

#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/orientation_list.hpp"
#include "kinematics/scene_model.hpp"
#include "motion/joint_trajectory.hpp"
#include "simulation/physics_perturbation.hpp"
#include "solver/synthesis_model.hpp"

namespace CLI {
class App;
class Validator;
}  // namespace CLI

namespace graspsynth::apps {

/// The flags of the physics perturbation (--physics, --friction-spread, --stiffness-range,
/// --damping-range, --mass-spread, --com-offset, --servo-force-spread, --fine-step,
/// --fine-step-probability), read into `options`; their defaults are those in `options`.
/// Call CheckPhysicsFlags after parsing.
void AddPhysicsPerturbationFlags(CLI::App* app, PhysicsPerturbationOptions* options);

/// Throws InputError naming the flag when the physics perturbation's flags are not valid.
void CheckPhysicsFlags(const PhysicsPerturbationOptions& options);

/// Adds --object NAME|FILE to a command that takes --scene: the object to use in place of the
/// scene's (a shipped object's name, models/objects/NAME.json, or an object file).
void AddObjectFlag(CLI::App* app, std::string* object);

/// Adds --at X,Y to a command that takes --theta: where the object stands on the table (its
/// centre, world, m); without it, at the scene's object centre. Read it with ParseAt.
void AddAtFlag(CLI::App* app, std::string* at);

/// The position of --at ("X,Y", two finite numbers of metres), or none for an empty text.
/// Throws InputError naming the flag and the text otherwise.
std::optional<Eigen::Vector2d> ParseAt(const std::string& text);

/// The object positions of --x and --y (each a list in the orientation-list grammar, metres):
/// every x at every y, y outermost; none when both are empty. Throws InputError when only one
/// is given or a list is malformed.
std::vector<Eigen::Vector2d> ParsePositionGrid(const std::string& x, const std::string& y);

/// Puts `trajectory`'s object at `at` (--at) when given, and checks that the object then
/// stands on the scene's table (SceneModel::CheckOnTable); throws InputError naming --at or
/// `file` (where the trajectory's "object_xy" came from) otherwise.
void PlaceTrajectoryObject(const SceneModel& scene, const std::optional<Eigen::Vector2d>& at,
                           const std::string& file, JointTrajectory* trajectory);

/// The scene of --scene (models/scene.json when empty) with the object of --object (the
/// scene's own when empty). With `needs_handle` (what the command does with it), an object
/// without a handle is refused before any work starts. Throws InputError naming the file at
/// fault, or the object and what needs its handle (kSynthesisNeedsHandle of
/// solver/synthesis_model.hpp for the commands that synthesize grasps).
SceneModel LoadScene(const std::string& scene, const std::string& object,
                     std::string_view needs_handle = {});

/// A check for an option that must be a number > 0: "must be > 0 (got VALUE)" (CLI11's
/// PositiveNumber prints the whole double range instead).
CLI::Validator PositiveValue();

/// Adds --no-physics-fallback (ValidatedSynthesisOptions::physics_fallback off) to `app`.
void AddPhysicsFallbackFlag(CLI::App* app, bool* no_physics_fallback);

/// --all-replays: every selection replay of every demonstration (SelectionOptions::early_stop
/// off).
void AddAllReplaysFlag(CLI::App* app, bool* all_replays);

/// A progress bar per named stage on stderr, redrawn in place on a terminal; elsewhere (logs,
/// pipes) a line "NAME: DONE/TOTAL (WHAT)" at every tenth of the stage. Thread-safe.
class ProgressBar {
 public:
  ProgressBar();

  /// Shows `done` of `total` steps of stage `name`, working on `what`. A new name starts a
  /// new bar.
  void Update(const std::string& name, int done, int total, const std::string& what);
  /// Ends the current bar's line.
  void Finish();

 private:
  bool tty_;
  bool started_ = false;
  std::string stage_;
  int last_tenth_ = -1;
  std::mutex mutex_;
};

}  // namespace graspsynth::apps
