// graspsynth teleop: the live teleoperation loop. One thread runs the control tick at --rate:
// it drains the UDP socket, steps the TeleopSession (teleop/teleop_session.hpp), sends the
// robot state back to the operator and publishes a viewer frame; the viewer's HTTP server has
// its own thread (viewer/viewer_server.hpp). graspsynth teleop-client: replays a demonstration
// log over UDP at its own rate, as a tracker and a glove would, and counts the states it gets.

#include "apps/teleop_command.hpp"

#include <arpa/inet.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <thread>

#include "apps/cli_helpers.hpp"
#include "apps/request_flags.hpp"
#include "apps/stop_signals.hpp"
#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/json_reader.hpp"
#include "common/orientation_list.hpp"
#include "common/stopwatch.hpp"
#include "kinematics/pose_math.hpp"
#include "kinematics/robot_file.hpp"
#include "learning_data/demo_log.hpp"
#include "request/teleop_request.hpp"
#include "scene/scene_model.hpp"
#include "simulation/simulation_model.hpp"
#include "teleop/calibration.hpp"
#include "teleop/packet_key.hpp"
#include "teleop/protocol.hpp"
#include "teleop/teleop_session.hpp"
#include "teleop/udp_link.hpp"
#include "viewer/viewer_scene.hpp"
#include "viewer/viewer_server.hpp"

namespace graspsynth::apps {
namespace {

using Clock = std::chrono::steady_clock;

// The server's files beside the request's options (request/teleop_request.hpp).
struct ServerOptions : request::TeleopRequest {
  std::string record_dir;
  std::string calibration;  // --calibration: graspsynth-teleop-config/1; empty: the shipped one
  std::string summary;
  std::string port_file;
  std::string key_file;
  std::string robot;  // --robot: empty for the shipped default
};

// The calibration of --calibration, or the shipped one.
teleop::TeleopCalibration LoadCalibration(const std::string& calibration) {
  return teleop::LoadTeleopCalibration(calibration.empty() ? teleop::DefaultTeleopCalibrationPath()
                                                           : std::filesystem::path(calibration));
}

// --config is a file of options; the calibration file it was before is refused, saying where it
// went.
void RefuseCalibrationConfig(const std::string& config) {
  RefuseFormerConfig(config, teleop::kTeleopConfigFormat, "a teleoperation calibration file",
                     "calibration file", "--calibration");
}

// The link's key of --key-file; none without.
std::optional<teleop::PacketKey> LoadLinkKey(const std::string& key_file) {
  if (key_file.empty()) return std::nullopt;
  return teleop::PacketKey::Load(key_file);
}

// 127.0.0.0/8: only this machine can reach the address.
bool IsLoopback(const std::string& address) {
  in_addr a{};
  return inet_pton(AF_INET, address.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24) == 127;
}

// The session's options of the request (its ranges checked when it was built) and the files.
teleop::TeleopOptions SessionOptions(const ServerOptions& opts) {
  teleop::TeleopOptions options;
  options.rate_hz = opts.rate_hz;
  options.timeout_s = opts.timeout_ms * 1e-3;
  options.end_hold_s = opts.end_hold_s;
  options.orientations_deg = ParseOrientationList(opts.orientations, "--orientations");
  options.object_xy = opts.at;
  options.record_dir = opts.record_dir;
  options.operator_name = opts.operator_name;
  options.calibration = LoadCalibration(opts.calibration);
  options.key = LoadLinkKey(opts.key_file);
  if (!options.key && !opts.insecure && !IsLoopback(opts.bind)) {
    throw InputError("--bind " + opts.bind +
                     " opens the link beyond this machine, and without a key anyone who reaches "
                     "the port could drive the robot: give --key-file FILE (graspsynth "
                     "teleop-keygen --out FILE writes one; the client takes the same file) or, "
                     "on a network you trust, --insecure");
  }
  return options;
}

// The viewer's HTTP server when --viewer-port asks for one.
std::unique_ptr<viewer::ViewerServer> StartViewer(const SimulationModel& model,
                                                  const ServerOptions& opts) {
  if (opts.viewer_port < 0) return nullptr;
  const viewer::ViewerCamera camera =
      opts.camera.empty()
          ? viewer::DefaultViewerCamera(model.scene())
          : viewer::ParseViewerCamera(opts.camera, viewer::DefaultViewerCamera(model.scene()));
  viewer::ViewerServerOptions viewer_options;
  viewer_options.port = opts.viewer_port;
  auto viewer = std::make_unique<viewer::ViewerServer>(
      viewer::ViewerSceneJson(model.robot(), model.scene(), camera), viewer_options);
  for (const std::string& missing : viewer->missing_assets()) {
    std::cerr << "graspsynth teleop: warning: " << missing
              << " is missing; run scripts/setup.sh (npm ci --prefix viewer) and rebuild\n";
  }
  std::cerr << "graspsynth teleop: viewer at " << viewer->url() << std::endl;
  return viewer;
}

void PrintTrial(const teleop::TrialRecord& t) {
  std::cerr << "graspsynth teleop: trial " << t.index << " (theta " << t.theta_deg
            << " deg): " << teleop::OutcomeName(t) << ": " << t.reason << "; "
            << (t.file.empty() ? "not written: " + t.not_written : "written to " + t.file.string())
            << std::endl;
}

// What the control loop measured.
struct LoopFigures {
  std::string end_reason = "end_of_session";
  uint64_t ticks = 0, late_ticks = 0;
  double busy_s = 0.0, busy_max_s = 0.0;
  double wall_s = 0.0;
};

// The control loop at the session's rate until the session is over.
LoopFigures RunControlLoop(const SimulationModel& model, const ServerOptions& opts,
                           teleop::TeleopSession* session, teleop::UdpLink* link,
                           viewer::ViewerServer* viewer) {
  const StopSignals signals;
  const Clock::time_point start = Clock::now();
  const auto tick = std::chrono::duration_cast<Clock::duration>(
      std::chrono::duration<double>(1.0 / session->options().rate_hz));
  Clock::time_point next = start;
  LoopFigures f;
  bool end_asked = false;
  std::vector<teleop::Datagram> incoming;
  while (true) {
    if (!end_asked && signals.stopped()) {
      f.end_reason = "signal";
      end_asked = true;
      session->RequestEnd();
    }
    if (!end_asked && opts.exit_after_s > 0.0 && SecondsSince(start) >= opts.exit_after_s) {
      f.end_reason = "exit_after";
      end_asked = true;
      session->RequestEnd();
    }
    const Clock::time_point tick_start = Clock::now();
    incoming.clear();
    link->Receive(&incoming);
    const teleop::TickResult r =
        session->Step(incoming, std::chrono::duration<double>(tick_start - start).count());
    if (!r.state_packet.empty() && r.peer) link->Send(r.state_packet, *r.peer);
    if (viewer) viewer->Publish(viewer::ViewerFrameJson(model.robot(), r.view));
    const double busy = SecondsSince(tick_start);
    f.busy_s += busy;
    f.busy_max_s = std::max(f.busy_max_s, busy);
    ++f.ticks;
    if (r.trial) PrintTrial(*r.trial);
    if (r.finished) break;
    next += tick;
    const Clock::time_point now = Clock::now();
    if (next < now) {
      ++f.late_ticks;
      next = now;  // late (a slow machine): do not try to catch up
    }
    std::this_thread::sleep_until(next);
  }
  f.wall_s = SecondsSince(start);
  return f;
}

// The model of --robot (the shipped default when empty) in the shipped scene. The glove map
// and the calibration are the PA-10 + Gifu Hand III's: another robot is refused.
SimulationModel LoadTeleopModel(const std::string& robot) {
  if (robot.empty()) return LoadDefaultSimulationModel();
  RobotModel model = LoadRobotOption(robot);
  RequireDefaultRobot(model, "--robot: teleop",
                      "the glove map and the calibration (graspsynth-teleop-config/1)");
  return SimulationModel(std::move(model), LoadSceneModel(DefaultSceneModelPath()));
}

int RunServer(const ServerOptions& opts) {
  const teleop::TeleopOptions options = SessionOptions(opts);
  const SimulationModel model = LoadTeleopModel(opts.robot);
  teleop::TeleopSession session(model, options);

  teleop::UdpLinkOptions link_options;
  link_options.address = opts.bind;
  link_options.port = opts.port;
  teleop::UdpLink link(link_options);
  if (!opts.port_file.empty()) WriteFileAtomically(opts.port_file, std::to_string(link.port()));
  std::unique_ptr<viewer::ViewerServer> viewer = StartViewer(model, opts);
  std::cerr << "graspsynth teleop: listening on udp " << opts.bind << ":" << link.port() << " at "
            << options.rate_hz << " Hz (" << (options.key ? "authenticated" : "not authenticated")
            << "; " << session.steps_per_tick() << " physics steps of "
            << session.physics_step() * 1e3 << " ms per tick); theta " << session.theta_deg()
            << " deg; Ctrl-C ends the session" << std::endl;

  const LoopFigures f = RunControlLoop(model, opts, &session, &link, viewer.get());
  if (viewer) viewer->Stop();
  if (!opts.summary.empty())
    WriteFileAtomically(opts.summary, session.SummaryJson(f.end_reason, f.wall_s));
  const teleop::PacketCounters& c = session.counters();
  std::cerr << "graspsynth teleop: session ended (" << f.end_reason << ") after " << f.wall_s
            << " s: " << f.ticks << " ticks (" << f.late_ticks << " late; processing "
            << (f.ticks ? f.busy_s / f.ticks * 1e3 : 0.0) << " ms mean, " << f.busy_max_s * 1e3
            << " ms max), " << c.received << " packets received, " << c.accepted << " accepted, "
            << c.dropped_total() << " dropped, " << c.states_sent << " states sent, "
            << session.trials().size() << " trials" << std::endl;
  return 0;
}

// The client's files beside the request's options (request/teleop_request.hpp).
struct ClientOptions : request::TeleopClientRequest {
  std::string replay;
  std::string calibration;  // --calibration: the server's; empty: the shipped one
  std::string key_file;
};

// The operator command of a log sample: the wrist pose in the tracker's frame, the fingers as
// joint values, the grasp and end events as button presses.
teleop::OperatorCommand CommandOf(const DemoSample& s, const teleop::TeleopCalibration& calibration,
                                  uint32_t sequence) {
  Eigen::Isometry3d X_WH = PoseFrom(s.p_WH, s.q_WH.normalized());
  const Eigen::Isometry3d X_TS = calibration.SensorInTracker(X_WH);
  teleop::OperatorCommand c;
  c.sequence = sequence;
  c.sender_time = s.t;
  c.p_TW = X_TS.translation();
  c.q_TW = Eigen::Quaterniond(X_TS.linear()).normalized();
  c.hand_mode = teleop::HandMode::kJoints;
  c.buttons = s.event == DemoEvent::kGrasp ? teleop::kGraspButton
              : s.event == DemoEvent::kEnd ? teleop::kEndTrialButton
                                           : 0;
  c.fingers = s.f;
  return c;
}

// What the client prints on stdout: counts, and the last state received.
nlohmann::json ClientReport(uint64_t commands, uint64_t states, uint64_t invalid,
                            const std::optional<teleop::RobotStateMessage>& last,
                            double duration_s) {
  nlohmann::json out = {{"commands_sent", commands},
                        {"end_of_session_sent", 3},
                        {"states_received", states},
                        {"invalid_received", invalid},
                        {"duration_s", duration_s}};
  if (last) {
    out["last_state"] = {{"trial", last->trial},
                         {"theta_deg", last->theta_deg},
                         {"flags", last->flags},
                         {"last_trial_succeeded", (last->flags & teleop::kLastTrialSucceeded) != 0},
                         {"object_position", {last->p_WO.x(), last->p_WO.y(), last->p_WO.z()}}};
  }
  return out;
}

int RunClient(const ClientOptions& opts) {
  const DemoLog log = ReadDemoLog(opts.replay);
  const teleop::TeleopCalibration calibration = LoadCalibration(opts.calibration);
  const std::optional<teleop::PacketKey> key = LoadLinkKey(opts.key_file);
  const teleop::PacketKey* key_ptr = key ? &*key : nullptr;
  const uint64_t server = teleop::ParsePeer(opts.host, opts.port);
  teleop::UdpLinkOptions link_options;
  link_options.address = "0.0.0.0";
  teleop::UdpLink link(link_options);

  uint64_t states = 0, invalid = 0;
  std::optional<teleop::RobotStateMessage> last;
  std::vector<teleop::Datagram> incoming;
  Clock::time_point last_state_time = Clock::now();
  const auto drain = [&] {
    incoming.clear();
    link.Receive(&incoming);
    for (const teleop::Datagram& d : incoming) {
      const teleop::DecodeResult r = teleop::Decode(d.bytes, key_ptr);
      if (r.packet && r.packet->kind == teleop::PacketKind::kState) {
        ++states;
        last = r.packet->state;
        last_state_time = Clock::now();
      } else {
        ++invalid;
      }
    }
  };

  const Clock::time_point start = Clock::now();
  const double t0 = log.samples.front().t;
  uint32_t sequence = 0;
  for (const DemoSample& s : log.samples) {
    const auto due = start + std::chrono::duration_cast<Clock::duration>(
                                 std::chrono::duration<double>((s.t - t0) / opts.speed));
    while (Clock::now() < due) {
      drain();
      link.WaitReadable(std::chrono::duration<double>(due - Clock::now()).count());
    }
    link.Send(teleop::EncodeCommand(CommandOf(s, calibration, sequence++), key_ptr), server);
  }
  const uint64_t commands = sequence;
  // end of session, three times (a lost datagram must not leave the server waiting).
  const double t_end = log.samples.back().t;
  for (int k = 0; k < 3; ++k) {
    link.Send(teleop::EncodeEndOfSession(sequence++, t_end, key_ptr), server);
    drain();
  }
  // the states of the server's last ticks (it judges the trial before it ends).
  last_state_time = Clock::now();
  while (SecondsSince(last_state_time) < opts.linger_s) {
    link.WaitReadable(0.05);
    drain();
  }
  std::cout << ClientReport(commands, states, invalid, last, SecondsSince(start)).dump()
            << std::endl;
  std::cerr << "graspsynth teleop-client: sent " << commands << " commands from " << opts.replay
            << " to " << teleop::PeerToString(server) << "; received " << states
            << " state packets (" << invalid << " invalid)" << std::endl;
  return states > 0 ? 0 : 1;
}

// --calibration FILE, of the server and of the client.
void AddCalibrationFlag(CLI::App* command, std::string* calibration) {
  command
      ->add_option("--calibration", *calibration,
                   "Calibration file (graspsynth-teleop-config/1); default: "
                   "examples/teleop_calibration.json")
      ->check(CLI::ExistingFile);
}

void AddServerCommand(CLI::App& app, int* exit_code) {
  auto opts = std::make_shared<ServerOptions>();
  CLI::App* teleop = app.add_subcommand(
      "teleop",
      "Live teleoperation server: UDP in, ODE in real time, state out, recording\n"
      "Live teleoperation: runs the ODE scene in real time at --rate and takes operator\n"
      "commands over UDP (wire format GSTP, README 'Teleoperation'): a wrist pose in the\n"
      "tracker's frame, mapped to the robot by the calibration file (--calibration), and 14\n"
      "glove values or 16 finger joints; buttons grasp, end of trial, next orientation. The arm\n"
      "follows through the analytic IK with a continuous arm angle (an unreachable target\n"
      "holds it), the hand through the glove map; every joint moves at most at its velocity\n"
      "cap. The robot and object state goes back to the sender every tick. Bad packets are\n"
      "dropped and counted by reason; a silence over --timeout-ms holds the robot still.\n"
      "With --record DIR every trial is judged after a 1 s hold (object centre >= 5 cm up,\n"
      "touching only the hand) and written as a v1 demonstration log. An end-of-session\n"
      "packet, Ctrl-C or SIGTERM end the session; --summary then gets a\n"
      "graspsynth-teleop-session/1 report (packet counters by reason, trials and outcomes).\n"
      "With --key-file every packet is authenticated (HMAC-SHA256, GSTP v2) and replays are\n"
      "refused by their sequence numbers; binding beyond 127.0.0.1 needs a key or --insecure.\n"
      "--config FILE is a file of the options below (graspsynth-options/1), not the\n"
      "calibration.");
  auto flags = std::make_shared<RequestFlags<request::TeleopRequest>>(
      teleop, request::TeleopServerOptions());
  teleop->add_option("--key-file", opts->key_file,
                     "Shared key (graspsynth teleop-keygen): take only packets authenticated "
                     "with it, and authenticate the states sent back");
  teleop->add_option("--record", opts->record_dir,
                     "Folder to write every trial to, as trial_NNN_thetaT.csv (v1 logs)");
  AddCalibrationFlag(teleop, &opts->calibration);
  AddRobotOption(teleop, &opts->robot);
  teleop->add_option(
      "--summary", opts->summary,
      "Write the session summary (graspsynth-teleop-session/1 JSON) here at the end");
  teleop->add_option("--port-file", opts->port_file,
                     "Write the UDP port listened on into this file once bound: with --port 0, a "
                     "script reads the free port there");
  teleop->callback([opts, flags, exit_code] {
    RefuseCalibrationConfig(flags->config());
    static_cast<request::TeleopRequest&>(*opts) = flags->Build();
    *exit_code = RunServer(*opts);
  });
}

void AddClientCommand(CLI::App& app, int* exit_code) {
  auto copts = std::make_shared<ClientOptions>();
  CLI::App* client = app.add_subcommand(
      "teleop-client",
      "Replay a demonstration log to a teleop server over UDP, as tracker and glove\n"
      "Replays a demonstration log (v1) to a 'graspsynth teleop' server over UDP at the log's\n"
      "rate (times --speed), as a tracker and a glove would: each wrist pose is mapped into\n"
      "the tracker's frame with the inverse of the calibration (--calibration, the server's),\n"
      "the fingers are sent as 16 joint values, the grasp and end events as button presses;\n"
      "then end of session. Prints the count of state packets received (JSON on stdout); exit\n"
      "status 1 when none came back. --config FILE is a file of the options below\n"
      "(graspsynth-options/1), not the calibration.");
  auto flags = std::make_shared<RequestFlags<request::TeleopClientRequest>>(
      client, request::TeleopClientOptions());
  client->add_option("--replay", copts->replay, "Demonstration log (graspsynth-demo/1 CSV)")
      ->required()
      ->check(CLI::ExistingFile);
  AddCalibrationFlag(client, &copts->calibration);
  client->add_option("--key-file", copts->key_file,
                     "The server's shared key: authenticate every packet with it (GSTP v2)");
  client->callback([copts, flags, exit_code] {
    RefuseCalibrationConfig(flags->config());
    static_cast<request::TeleopClientRequest&>(*copts) = flags->Build();
    *exit_code = RunClient(*copts);
  });
}

void AddKeygenCommand(CLI::App& app, int* exit_code) {
  auto out = std::make_shared<std::string>();
  CLI::App* keygen = app.add_subcommand(
      "teleop-keygen",
      "Write a new shared key that authenticates the teleoperation link\n"
      "Writes a new shared key for the teleoperation link: 32 random bytes (OpenSSL) in hex, in\n"
      "a file readable by its owner only (mode 0600). Give the same file to 'teleop --key-file'\n"
      "and 'teleop-client --key-file'. An existing file is never overwritten.");
  keygen->add_option("--out", *out, "Key file to create")->required();
  keygen->callback([out, exit_code] {
    teleop::WriteNewPacketKey(*out);
    std::cerr << "graspsynth teleop-keygen: wrote a new key to " << *out << std::endl;
    *exit_code = 0;
  });
}

}  // namespace

void AddTeleopCommands(CLI::App& app, int* exit_code) {
  AddServerCommand(app, exit_code);
  AddClientCommand(app, exit_code);
  AddKeygenCommand(app, exit_code);
}

}  // namespace graspsynth::apps
