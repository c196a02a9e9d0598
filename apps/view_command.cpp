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
#include "common/stopwatch.hpp"
#include "kinematics/robot_description.hpp"
#include "learning_data/demo_log.hpp"
#include "motion/joint_trajectory.hpp"
#include "request/view_request.hpp"
#include "scene/scene_model.hpp"
#include "viewer/viewer_replay.hpp"
#include "viewer/viewer_scene.hpp"
#include "viewer/viewer_server.hpp"

namespace graspsynth::apps {
namespace {

// The command's files beside the request's options (request/view_request.hpp).
struct ViewOptions : request::ViewRequest {
  std::string trajectory;
  std::string log;
  std::string robot;
  std::string scene;
  std::string object;  // --object: a shipped object's name or an object file
};

// The replay of --trajectory or --log, or the robot at rest with neither.
viewer::ViewerReplay LoadReplay(const ViewOptions& opts, const RobotModel& robot,
                                const SceneModel& scene) {
  const std::optional<Eigen::Vector2d>& at = opts.at;
  if (at && opts.trajectory.empty()) {
    throw InputError(
        "--at moves the object of a --trajectory (a log's object stands where it "
        "was logged)");
  }
  if (!opts.trajectory.empty()) {
    JointTrajectory trajectory = LoadJointTrajectory(opts.trajectory, robot.arm, robot.hand);
    PlaceTrajectoryObject(scene, at, opts.trajectory, &trajectory);
    return viewer::ReplayOfTrajectory(std::move(trajectory), opts.trajectory);
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
  const bool ends = !opts.trajectory.empty() || !opts.log.empty();
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
  const RobotModel robot = LoadRobotModel(opts.robot.empty() ? DefaultRobotDescriptionPath()
                                                             : std::filesystem::path(opts.robot));
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
      "Browser viewer: replay a trajectory or a demonstration log in a web page\n"
      "Serves a page (three.js) on this machine and replays a file in it.\n"
      "Open the URL printed on stderr. --trajectory plays a graspsynth-trajectory/1 file (a\n"
      "grasp's joint trajectory); --log a demonstration log (its wrist poses through the\n"
      "analytic IK with a continuous arm angle, the object at its logged position); with\n"
      "neither, the robot is shown at rest. The replay starts with the first page (or at once\n"
      "with --no-wait) and runs at the file's rate (times --speed) until its end (plus --hold),\n"
      "or for ever with --loop; Ctrl-C or SIGTERM stop it cleanly.");
  auto flags = std::make_shared<RequestFlags<request::ViewRequest>>(view, request::ViewOptions());
  auto* source = view->add_option_group("source", "What to replay");
  source->add_option("--trajectory", opts->trajectory, "Trajectory file (graspsynth-trajectory/1)")
      ->check(CLI::ExistingFile);
  source->add_option("--log", opts->log, "Demonstration log (graspsynth-demo/1 CSV)")
      ->check(CLI::ExistingFile);
  source->require_option(0, 1);
  view->add_option("--robot", opts->robot,
                   "Robot description (URDF); default: models/pa10_gifu3.urdf of this checkout "
                   "or $GRASPSYNTH_DATA_DIR");
  view->add_option("--scene", opts->scene,
                   "Scene description (graspsynth-scene/2); default: models/scene.json");
  AddObjectFlag(view, &opts->object);
  view->callback([opts, flags, exit_code] {
    static_cast<request::ViewRequest&>(*opts) = flags->Build();
    *exit_code = RunView(*opts);
  });
}

}  // namespace graspsynth::apps
