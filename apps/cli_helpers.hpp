#pragma once

/// @file
/// Pieces shared by the commands: a list of orientations from the command line
/// (ParseOrientationList, common/orientation_list.hpp), the scene and object flags, the physics
/// perturbation's flags, and a progress bar on stderr.

#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "apps/request_flags.hpp"
#include "common/job_runner.hpp"
#include "common/orientation_list.hpp"
#include "kinematics/robot_description.hpp"
#include "motion/joint_trajectory.hpp"
#include "scene/scene_model.hpp"
#include "simulation/physics_perturbation.hpp"
#include "solver/synthesis_model.hpp"

namespace CLI {
class App;
}  // namespace CLI

namespace graspsynth::apps {

/// Refuses a --config `config` (a file of options, graspsynth-options/1) that is a file of the
/// format `format`, which this command once took as --config and now takes as `flag`: throws
/// InputError "--config 'FILE' is <what> (<format>): the <name> is now <flag> FILE; ...".
/// Nothing for an empty `config` or another file.
void RefuseFormerConfig(const std::string& config, std::string_view format, const char* what,
                        const char* name, const char* flag);

/// Adds --robot NAME|FILE to a command, with the one help text every command shows: a shipped
/// robot's name, a robot file or a URDF; empty for the default (kinematics/robot_file.hpp's
/// LoadRobotOption reads it). `what` adds what this command reads of it ("" for nothing).
void AddRobotOption(CLI::App* app, std::string* robot, std::string_view what = {});

/// Adds --object NAME|FILE to a command that takes --scene: the object to use in place of the
/// scene's (a shipped object's name, models/objects/NAME.json, or an object file).
void AddObjectFlag(CLI::App* app, std::string* object);

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

/// The runner of this process's job stages (common/job_runner.hpp): spread over an MPI job's
/// processes when main() started one (SetProcessRunner), else this process's threads.
JobRunner& ProcessRunner();
/// Makes `runner` the process's runner (main(), before any command runs).
void SetProcessRunner(std::unique_ptr<JobRunner> runner);

/// Adds --resume to a long command: take the finished jobs of an earlier, interrupted run of
/// the same command with the same arguments and inputs, and run only the others.
void AddResumeFlag(CLI::App* app, bool* resume);

/// The identity of the run of `command` (RunIdentity, common/job_runner.hpp): the command's
/// name and the values given to each of its options (as given; an option not given counts as
/// its default, or as empty where the command does not show its default), but --threads,
/// --resume and --quiet, which change no result. The caller adds its input files.
RunIdentity CommandIdentity(const CLI::App& command);

/// Adds the fingerprints of the robot description, the scene file and the object file of
/// --robot, --scene and --object (each empty for the shipped default) to `identity`. The files
/// these name in turn (a scene's own object file, an object's meshes) are not fingerprinted.
void AddModelFiles(const std::string& robot, const std::string& scene, const std::string& object,
                   RunIdentity* identity);

/// The resume folder of a run writing to `folder` (ProcessRunner's finished jobs go there as
/// they come in, and `--resume` takes them back), on the process that writes the outputs;
/// nothing on the others. Prints on stderr what a resume found. Throws InputError when
/// `resume` is set and the earlier run differs from `identity` (naming what differs).
class RunCheckpoint {
 public:
  RunCheckpoint(const std::filesystem::path& folder, const RunIdentity& identity, bool resume);
  ~RunCheckpoint();
  RunCheckpoint(const RunCheckpoint&) = delete;
  RunCheckpoint& operator=(const RunCheckpoint&) = delete;
  /// The run's outputs are written: says on stderr, for a resumed run, how many kept jobs were
  /// taken and how many recomputed (with the first reasons), and removes the folder.
  void Done();

 private:
  std::optional<ResumeFolder> folder_;
};

/// A progress bar per named stage on stderr, redrawn in place on a terminal; elsewhere (logs,
/// pipes) a line "NAME: DONE/TOTAL (WHAT)" at every tenth of the stage; nothing on the
/// processes of an MPI job that do not write the outputs. Thread-safe.
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
  bool quiet_;
  bool started_ = false;
  std::string stage_;
  int last_tenth_ = -1;
  std::mutex mutex_;
};

}  // namespace graspsynth::apps
