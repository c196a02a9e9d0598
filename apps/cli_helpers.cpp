#include "apps/cli_helpers.hpp"

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/json_reader.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "request/physics_options.hpp"
#include "scene/base_frame.hpp"
#include "scene/object_model.hpp"

namespace graspsynth::apps {

void RefuseFormerConfig(const std::string& config, std::string_view format, const char* what,
                        const char* name, const char* flag) {
  if (config.empty()) return;
  const JsonReader root = JsonReader::Load(config);
  if (root.IsObject() && root.Field("format").IsString() &&
      root.Field("format").AsString() == format) {
    throw InputError("--config '" + config + "' is " + what + " (" + std::string(format) +
                     "): the " + name + " is now " + flag +
                     " FILE; --config FILE takes a file of this command's options "
                     "(graspsynth-options/1)");
  }
}

void AddRobotOption(CLI::App* app, std::string* robot, std::string_view what) {
  app->add_option("--robot", *robot,
                  "The robot: a shipped robot's name ('graspsynth robots' lists them, e.g. "
                  "iiwa14_allegro), a robot file (*.json, graspsynth-robot/1) or a URDF" +
                      std::string(what) +
                      "; default: models/pa10_gifu3.urdf of the data folder (this checkout or "
                      "$GRASPSYNTH_DATA_DIR)");
}

void AddObjectFlag(CLI::App* app, std::string* object) {
  app->add_option("--object", *object,
                  "The object to grasp in place of the scene's: a shipped object's name (a file "
                  "models/objects/NAME.json) or an object description file "
                  "(graspsynth-object/1); default: the object the scene names");
}

void PlaceTrajectoryObject(const SceneModel& scene, const std::optional<Eigen::Vector2d>& at,
                           const std::string& file, JointTrajectory* trajectory) {
  // --at is in the study's world; the scene (a model's) may be in the robot's base frame.
  if (at) trajectory->object_xy = TablePointInScene(scene, *at);
  if (!trajectory->object_xy) return;
  try {
    scene.CheckOnTable(*trajectory->object_xy);
  } catch (const InputError& e) {
    throw InputError((at ? std::string("--at: ") : file + ": object_xy: ") + e.what());
  }
}

SceneModel LoadScene(const std::string& scene, const std::string& object,
                     std::string_view needs_handle) {
  SceneModel out = LoadSceneModel(
      scene.empty() ? DefaultSceneModelPath() : std::filesystem::path(scene), object);
  if (!needs_handle.empty()) out.object.Handle(needs_handle);
  return out;
}

namespace {

std::unique_ptr<JobRunner>& TheProcessRunner() {
  static std::unique_ptr<JobRunner> runner = std::make_unique<LocalJobRunner>();
  return runner;
}

}  // namespace

JobRunner& ProcessRunner() { return *TheProcessRunner(); }

void SetProcessRunner(std::unique_ptr<JobRunner> runner) { TheProcessRunner() = std::move(runner); }

void AddResumeFlag(CLI::App* app, bool* resume) {
  app->add_flag("--resume", *resume,
                "Take the finished jobs of an earlier run of this command that was stopped "
                "(killed, preempted) and run only the others: the outputs are the bytes of an "
                "uninterrupted run. The earlier run's arguments and inputs must be the same "
                "(a difference is refused, named). Finished jobs are kept as they come in, in "
                "a folder beside the outputs that the finished run removes");
}

RunIdentity CommandIdentity(const CLI::App& command) {
  RunIdentity identity;
  identity.command = command.get_name();
  for (const CLI::Option* option : command.get_options()) {
    const std::string name = option->get_name();
    if (name == "--threads" || name == "--resume" || name == "--help" || name == "--quiet") {
      continue;  // none of them changes a result
    }
    std::string value;
    for (const std::string& r : option->results()) value += (value.empty() ? "" : " ") + r;
    // an option left at its default counts as its default's value, where CLI11 knows it.
    identity.Add(name, option->results().empty() ? option->get_default_str() : value);
  }
  return identity;
}

void AddModelFiles(const std::string& robot, const std::string& scene, const std::string& object,
                   RunIdentity* identity) {
  if (robot.empty()) {
    identity->AddFile("robot file", DefaultRobotDescriptionPath());
  } else {
    // a robot file and its URDF (a shipped robot's name is its robot file).
    const std::filesystem::path path = ResolveRobotPath(robot);
    identity->AddFile("robot file", path);
    if (path.extension() == ".json") identity->AddFile("robot URDF", LoadRobotFile(path).urdf);
  }
  identity->AddFile("scene file",
                    scene.empty() ? DefaultSceneModelPath() : std::filesystem::path(scene));
  if (!object.empty()) identity->AddFile("object file", ResolveObjectPath(object));
}

RunCheckpoint::RunCheckpoint(const std::filesystem::path& folder, const RunIdentity& identity,
                             bool resume) {
  if (!ProcessRunner().writes_outputs()) return;
  folder_.emplace(folder, identity, resume);
  ProcessRunner().set_resume_folder(&*folder_);
  if (resume) {
    std::fprintf(
        stderr, "%s\n",
        folder_->resumed()
            ? ("resuming the run kept in " + folder.string()).c_str()
            : ("--resume: no earlier run in " + folder.string() + ": starting afresh").c_str());
  }
}

RunCheckpoint::~RunCheckpoint() {
  if (folder_) ProcessRunner().set_resume_folder(nullptr);
}

void RunCheckpoint::Done() {
  if (!folder_) return;
  const ResumeSummary summary = folder_->summary();
  if (folder_->resumed()) {
    std::string line = "resumed: " + std::to_string(summary.taken) + " finished jobs taken from " +
                       folder_->folder().string() + ", " + std::to_string(summary.recomputed) +
                       " recomputed";
    for (const std::string& why : summary.reasons) line += "\n  recomputed " + why;
    if (summary.recomputed > static_cast<int>(summary.reasons.size())) line += "\n  ...";
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  folder_->Remove();
}

ProgressBar::ProgressBar()
    : tty_(::isatty(STDERR_FILENO) != 0), quiet_(!ProcessRunner().writes_outputs()) {}

void ProgressBar::Update(const std::string& name, int done, int total, const std::string& what) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (total <= 0 || quiet_) return;
  if (!started_ || name != stage_) {
    if (tty_ && started_) std::fprintf(stderr, "\n");
    stage_ = name;
    last_tenth_ = -1;
    started_ = true;
  }
  const int width = 30;
  const int filled = std::min(done, total) * width / total;
  if (tty_) {
    std::fprintf(stderr, "\r%-9s [%s%s] %d/%d  %-36.36s", name.c_str(),
                 std::string(filled, '#').c_str(), std::string(width - filled, ' ').c_str(), done,
                 total, what.c_str());
  } else if (done * 10 / total != last_tenth_) {
    last_tenth_ = done * 10 / total;
    if (what.empty()) {
      std::fprintf(stderr, "%s: %d/%d\n", name.c_str(), done, total);
    } else {
      std::fprintf(stderr, "%s: %d/%d (%s)\n", name.c_str(), done, total, what.c_str());
    }
  }
  std::fflush(stderr);
}

void ProgressBar::Finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tty_ && started_) std::fprintf(stderr, "\n");
  started_ = false;
}

}  // namespace graspsynth::apps
