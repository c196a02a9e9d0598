// graspsynth view: the browser viewer with a replay. The server and the drawing are the
// teleoperation viewer's (viewer/viewer_server.hpp, viewer/viewer_scene.hpp); this command only
// produces the frames: from a trajectory file (the samples' joints), a demonstration log (the
// wrist poses through the analytic IK with a continuous arm angle) or, with neither, the robot
// at rest.

#include "apps/view_command.hpp"

#include <chrono>
#include <cmath>
#include <csignal>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "apps/stop_signals.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"
#include "common/stopwatch.hpp"
#include "gate/grasp_file.hpp"
#include "kinematics/robot_description.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/joint_trajectory.hpp"
#include "request/simulate_request.hpp"
#include "request/view_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial_record.hpp"
#include "viewer/viewer_replay.hpp"
#include "viewer/viewer_scene.hpp"
#include "viewer/viewer_server.hpp"

namespace graspsynth::apps {
namespace {

// The command's files beside the request's options (request/view_request.hpp).
struct ViewOptions : request::ViewRequest {
  std::string trajectory;
  std::string trial;  // --trial: a graspsynth-trial-record/1 file
  std::string log;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
};

// The format of a JSON file when it names one ("" otherwise): to tell a trial record from a
// trajectory or grasp file.
std::string FormatOf(const std::string& path) {
  const JsonReader doc = JsonReader::Load(path, input_kind::kTrajectory);
  if (!doc.IsObject() || !doc.Field("format").IsString()) return "";
  return doc.String("format");
}

// The nominal trial of `trajectory` (simulate's defaults: request::SimulateRequest{}), its states
// recorded at the viewer's frame rate, as a trial record; its brief report on stderr.
TrialRecord SimulateForView(const ViewOptions& opts, const RobotModel& robot,
                            const SceneModel& scene, const JointTrajectory& trajectory) {
  TrialOptions trial = request::ToTrialOptions(request::SimulateRequest{});
  trial.record_interval = 1.0 / opts.rate_hz;
  std::cerr << "graspsynth view: simulating the nominal trial of " << opts.trajectory << std::endl;
  RecordedTrial trial_run =
      RunRecordedTrial(SimulationModel(robot, scene), trajectory, trial, opts.trajectory);
  std::cerr << "graspsynth view: nominal trial: " << trial_run.result.BriefReport() << "\n";
  return std::move(trial_run.record);
}

// The replay of a trial record (--trial, or a --trajectory file that is one).
viewer::ViewerReplay TrialReplay(const ViewOptions& opts, const std::string& path) {
  if (opts.at) {
    throw InputError("--at moves the object of a trajectory; the trial record " + path +
                     " was simulated where it says");
  }
  if (opts.joints_only) {
    throw InputError("--joints-only plays a trajectory's joint commands; the trial record " + path +
                     " is a simulated trial");
  }
  return viewer::ReplayOfTrial(LoadTrialRecord(path), path);
}

// The replay of --trajectory (a trajectory, grasp or trial record file), --trial or --log, or
// the robot at rest with none.
viewer::ViewerReplay LoadReplay(const ViewOptions& opts, const RobotModel& robot,
                                const SceneModel& scene) {
  const std::optional<Eigen::Vector2d>& at = opts.at;
  if (at && opts.trajectory.empty()) {
    throw InputError(
        "--at moves the object of a --trajectory (a log's object stands where it "
        "was logged)");
  }
  if (opts.joints_only && opts.trajectory.empty()) {
    throw InputError("--joints-only plays a --trajectory's joint commands without the physics");
  }
  if (!opts.trial.empty() || !opts.trajectory.empty() || !opts.log.empty()) {
    RequireDefaultRobot(robot, "--robot: view",
                        "a trajectory, grasp, trial record or demonstration log file");
  }
  if (!opts.trial.empty()) return TrialReplay(opts, opts.trial);
  if (!opts.trajectory.empty()) {
    if (FormatOf(opts.trajectory) == kTrialRecordFormat) return TrialReplay(opts, opts.trajectory);
    // a graspsynth-trajectory/1 file, or the "trajectory" member of a graspsynth-grasp/1 file.
    JointTrajectory trajectory = LoadTrajectoryOrGraspFile(opts.trajectory, robot.arm, robot.hand);
    PlaceTrajectoryObject(scene, at, opts.trajectory, &trajectory);
    if (opts.joints_only) return viewer::ReplayOfTrajectory(std::move(trajectory), opts.trajectory);
    return viewer::ReplayOfTrial(SimulateForView(opts, robot, scene, trajectory), opts.trajectory);
  }
  if (!opts.log.empty()) {
    viewer::ViewerReplay replay = viewer::ReplayOfLog(robot, ReadDemoLog(opts.log));
    if (replay.unreached > 0) {
      std::cerr << "graspsynth view: " << replay.unreached << " of "
                << replay.trajectory.samples.size()
                << " wrist poses of the log have no IK solution; the arm holds there\n";
    }
    return replay;
  }
  return viewer::RestReplay();
}

using Clock = std::chrono::steady_clock;

// How a replay went.
struct PlayFigures {
  bool ended = false;  // the replay reached its end (and the hold)
  uint64_t published = 0;
};

// Publishes the replay's frames at --rate until its end (plus --hold), for ever with --loop,
// or until `out_of_time`.
template <typename OutOfTime>
PlayFigures PlayReplay(const ViewOptions& opts, const RobotModel& robot, const SceneModel& scene,
                       const viewer::ViewerReplay& replay, viewer::ViewerServer* server,
                       const OutOfTime& out_of_time) {
  const bool ends = !opts.trajectory.empty() || !opts.trial.empty() || !opts.log.empty();
  // replay time runs from the first sample's time to the last one's.
  const double t_first = replay.start_time();
  const double t_last = replay.end_time();
  const auto tick = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / opts.rate_hz));

  // the first frame; the replay's clock starts when a page first gets it (unless --no-wait).
  server->Publish(viewer::ViewerFrameJson(robot, viewer::ReplayStateAt(replay, scene, t_first)));
  if (!opts.no_wait) {
    std::cerr << "graspsynth view: waiting for a browser to open the page" << std::endl;
    while (server->counters().frame_requests == 0 && !out_of_time()) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }

  const Clock::time_point replay_start = Clock::now();
  Clock::time_point next = replay_start;
  std::optional<Clock::time_point> ended;
  PlayFigures figures;
  figures.published = 1;
  while (!out_of_time()) {
    const double elapsed = SecondsSince(replay_start) * opts.speed;
    double t = t_first + elapsed;
    if (opts.loop && t_last > t_first) t = t_first + std::fmod(elapsed, t_last - t_first);
    if (ends && !opts.loop && t >= t_last && !ended) ended = Clock::now();
    viewer::ViewerState state = viewer::ReplayStateAt(replay, scene, t);
    if (ended) state.text += " | replay done";
    server->Publish(viewer::ViewerFrameJson(robot, state));
    ++figures.published;
    if (ended && SecondsSince(*ended) >= opts.hold_s) break;
    next += tick;
    const Clock::time_point now = Clock::now();
    if (next < now) next = now;  // late (a slow machine): do not try to catch up
    std::this_thread::sleep_until(next);
  }
  figures.ended = ended.has_value();
  return figures;
}

// `opts`' numbers are in their ranges: the request's options checked them (request/view_request).
int RunView(const ViewOptions& opts) {
  const RobotModel robot = LoadRobotOption(opts.robot);
  const SceneModel scene = LoadScene(opts.scene, opts.object);
  const viewer::ViewerCamera camera =
      opts.camera.empty()
          ? viewer::DefaultViewerCamera(scene)
          : viewer::ParseViewerCamera(opts.camera, viewer::DefaultViewerCamera(scene));
  const viewer::ViewerReplay replay = LoadReplay(opts, robot, scene);

  viewer::ViewerServerOptions server_options;
  server_options.address = opts.address;
  server_options.port = opts.port;
  viewer::ViewerServer server(viewer::ViewerSceneJson(robot, scene, camera), server_options);
  for (const std::string& missing : server.missing_assets()) {
    std::cerr << "graspsynth view: warning: " << missing
              << " is missing; run scripts/setup.sh (npm ci --prefix viewer) and rebuild\n";
  }
  const StopSignals signals;
  std::cerr << "graspsynth view: open " << server.url() << " in a browser (Ctrl-C to stop)"
            << std::endl;
  const Clock::time_point started = Clock::now();
  const auto out_of_time = [&] {
    return signals.stopped() ||
           (opts.exit_after_s > 0.0 && SecondsSince(started) >= opts.exit_after_s);
  };
  const PlayFigures figures = PlayReplay(opts, robot, scene, replay, &server, out_of_time);
  server.Stop();
  const viewer::ViewerServerCounters counters = server.counters();
  std::cerr << "graspsynth view: "
            << (signals.stopped() ? "stopped by a signal"
                : figures.ended   ? "replay done"
                                  : "stopped (--exit-after)")
            << "; " << figures.published << " frames published, " << counters.frame_requests
            << " sent to the page, " << counters.requests << " requests (" << counters.bad_requests
            << " bad); " << counters.connections << " connections (" << counters.timed_out
            << " timed out, " << counters.evicted << " closed to make room, " << counters.refused
            << " refused)" << std::endl;
  return 0;
}

}  // namespace

void AddViewCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<ViewOptions>();
  CLI::App* view = app.add_subcommand(
      "view",
      "Browser viewer: a grasp played as simulated, a trial record or a demonstration log\n"
      "Serves a page (three.js) on this machine and replays a file in it.\n"
      "Open the URL printed on stderr. --trajectory takes a graspsynth-trajectory/1 file or a\n"
      "graspsynth-grasp/1 file (its \"trajectory\"): the command runs its nominal trial in the\n"
      "ODE simulation (simulate's defaults) and plays it as simulated: the joints and the\n"
      "object from the physics, the object-hand contacts as dots, the outcome in a banner\n"
      "(a failed grasp shows FAILED and its reason); --joints-only plays the joint commands\n"
      "alone, the object standing still. --trial plays a trial record (simulate --trial-record;\n"
      "--trajectory recognises one too). --log plays a demonstration log (its wrist poses\n"
      "through the analytic IK with a continuous arm angle, the object at its logged\n"
      "position); with none, the robot is shown at rest. The replay runs at the file's rate\n"
      "(times --speed) until its end (plus --hold), or for ever with --loop; Ctrl-C or\n"
      "SIGTERM stop it cleanly. More, with screenshots: docs/viewer.md.");
  auto flags = std::make_shared<RequestFlags<request::ViewRequest>>(view, request::ViewOptions());
  auto* source = view->add_option_group("source", "What to replay");
  source
      ->add_option("--trajectory", opts->trajectory,
                   "Trajectory, grasp or trial record file (graspsynth-trajectory/1, "
                   "graspsynth-grasp/1, graspsynth-trial-record/1)")
      ->check(CLI::ExistingFile);
  source
      ->add_option("--trial", opts->trial,
                   "Trial record to play as simulated (graspsynth-trial-record/1)")
      ->check(CLI::ExistingFile);
  source->add_option("--log", opts->log, "Demonstration log (graspsynth-demo/1 CSV)")
      ->check(CLI::ExistingFile);
  source->require_option(0, 1);
  AddRobotOption(view, &opts->robot);
  view->add_option("--scene", opts->scene,
                   "Scene description (graspsynth-scene/2); default: models/scene.json");
  AddObjectFlag(view, &opts->object);
  view->callback([opts, flags, exit_code] {
    static_cast<request::ViewRequest&>(*opts) = flags->Build();
    *exit_code = RunView(*opts);
  });
}

}  // namespace graspsynth::apps
