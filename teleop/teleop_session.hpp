#pragma once

/// @file
/// The live teleoperation loop without its sockets and its clock: a TeleopSession owns the ODE
/// world (simulation/simulation_data.hpp) and, once per control tick, takes the datagrams that
/// came in since the last tick and the current time, applies the newest valid operator command
/// to the robot, simulates one tick (1 / rate_hz s) and returns the robot state to stream back.
/// The command (`graspsynth teleop`) feeds it from a UDP socket at the control rate; tests and
/// benchmarks call Step() directly, with made-up times.
///
/// Per tick:
/// 1. every datagram is decoded and checked (teleop/protocol.hpp: framing, values, then the
///    sequence number); a bad one is counted by its DropReason and never applied. A robot state
///    sent to the server counts as kUnknownKind. Of the valid commands of a tick the newest
///    drives the robot; the button bits of all of them count (a press is a 0 -> 1 change of a
///    bit between consecutive valid commands).
/// 2. the wrist target X_WH = calibration.WristInWorld(X_TS) goes through the analytic IK with a
///    continuous arm angle: the branch of the previous solution is kept, the arm angle nearest
///    the previous one (motion/joint_space.hpp SolveWristPose); a target without a solution
///    holds the previous one (StateFlag::kOutOfReach). The fingers: glove values through the
///    glove map (teleop/glove_map.hpp), or joint values clamped to the hand's limits.
/// 3. the commanded joints move toward their targets by at most the URDF velocity cap of each
///    joint per second, whatever the operator sends; a silence longer than timeout_s (or no
///    command yet) freezes the commands where they are: the robot holds still.
/// 4. the physics: the tick is split into equal steps of at most max_physics_step, each with
///    targets interpolated along the tick; the arm follows its controller kinematically (as in
///    the simulation's fast path, simulation/trial.hpp), the hand and the object are dynamic;
///    free space runs without contact detail until the robot comes near the object (the
///    stepping of the offline trials, StepTrialWorld in simulation/trial_judge.hpp).
///
/// Trials. A trial starts with the first command after a reset of the world and is recorded
/// tick by tick: the wrist pose reached, the commanded fingers, the button event, the object
/// centre. The grasp button marks the current sample as the grasp (a later press moves the
/// mark). The end-of-trial button starts a hold of end_hold_s (commands are ignored, the robot
/// keeps its last command), then the trial is judged by the judgement of the offline trials
/// (simulation/trial_judge.hpp: JudgeTrial, every TrialOutcome; an arm joint commanded beyond
/// its limit or the arm on the table during the trial decides it when it happens first),
/// written as a v1 demonstration log when record_dir is set and it has a grasp mark, and the
/// world is reset at the same orientation with the robot at its rest configuration. The
/// next-orientation button abandons an open trial (not written) and resets the world at the
/// next orientation of the list (after the last, the first again). An ODE failure or a
/// numerical instability ends the trial as "unstable" at once and resets the world: nothing an
/// operator sends can crash the session.

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "learning_data/demo_log.hpp"
#include "simulation/simulation_model.hpp"
#include "simulation/trial_judge.hpp"
#include "teleop/calibration.hpp"
#include "teleop/glove_map.hpp"
#include "teleop/protocol.hpp"
#include "viewer/viewer_scene.hpp"

namespace graspsynth::teleop {

/// The `format` value of a session summary.
inline constexpr std::string_view kTeleopSessionFormat = "graspsynth-teleop-session/1";

/// Options of a session.
struct TeleopOptions {
  double rate_hz = 60.0;  ///< control rate, Hz: one Step() simulates 1 / rate_hz s
  /// Longest physics step, s; a tick is split into ceil(tick / max_physics_step) equal steps.
  double max_physics_step = 0.004;
  /// A silence longer than this (s) since the last valid command holds the robot still.
  double timeout_s = 0.2;
  /// After the end-of-trial button the robot holds its last command this long (s) before the
  /// trial is judged (DESIGN.md: a hold of at least 1 s).
  double end_hold_s = 1.0;
  /// The judgement of a trial (simulation/trial_judge.hpp), as in the offline trials; success
  /// needs the object centre judge.lift_threshold above its rest height at the judgement.
  TrialJudgeOptions judge;
  /// Object orientations theta (deg) the session walks through, in order; at least one.
  std::vector<double> orientations_deg = {20, 30, 40, 50, 60, 70, 80, 90, 100};
  /// The object centre on the table, world, m; empty: the scene's object centre. On the
  /// scene's table (SceneModel::CheckOnTable, checked when the session starts).
  std::optional<Eigen::Vector2d> object_xy;
  /// Folder the trials are written to (one v1 log each); empty: nothing is written.
  std::filesystem::path record_dir;
  /// Free text written as the logs' `operator` key (none when empty).
  std::string operator_name;
  TeleopCalibration calibration;  ///< tracker frame and wrist offset
  /// Glove-to-joint map; std::nullopt: GloveMap::Default of the model's hand.
  std::optional<GloveMap> glove_map;
  /// The link's shared key: with one, only authenticated commands (version 2, a tag that
  /// verifies) are taken and the states are sent authenticated; without, only version 1.
  std::optional<PacketKey> key;

  /// True when every value is finite and in range; otherwise false with the reason.
  bool IsValid(std::string* why) const;
};

/// A datagram as it came in: the bytes and an opaque id of its sender (UdpLink packs the IPv4
/// address and port into it), to which the state is streamed back.
struct Datagram {
  std::vector<uint8_t> bytes;
  uint64_t peer = 0;
};

/// Packet counters of a session.
struct PacketCounters {
  uint64_t received = 0;          ///< datagrams given to Step()
  uint64_t accepted = 0;          ///< passed every check (commands and end of session)
  uint64_t commands_applied = 0;  ///< valid commands that drove the robot (the newest of a tick)
  uint64_t ignored_while_judging = 0;  ///< valid commands during the hold before a judgement
  std::array<uint64_t, kDropReasonCount> dropped{};  ///< by DropReason
  uint64_t states_sent = 0;                          ///< state packets produced for a peer

  /// Sum of the drop counters.
  uint64_t dropped_total() const;
};

/// One trial of the session, as the summary lists it.
struct TrialRecord {
  int index = 0;           ///< 1-based, in the order the trials ended
  double theta_deg = 0.0;  ///< object orientation, deg
  /// How the trial was judged; std::nullopt: abandoned (the next orientation was chosen or
  /// the session ended first), not judged.
  std::optional<TrialOutcome> outcome;
  bool success = false;        ///< outcome == TrialOutcome::kSuccess
  std::string reason;          ///< one sentence with the deciding figures
  double lift_m = 0.0;         ///< object centre above its rest height at the end, m
  double duration_s = 0.0;     ///< simulated time of the trial, s
  size_t samples = 0;          ///< recorded samples
  bool has_grasp = false;      ///< the grasp button was pressed during the trial
  std::filesystem::path file;  ///< the written log; empty when not written
  std::string not_written;     ///< why no log was written (empty when written)
};

/// The name of a trial's outcome in the summary, the logs and on the console: ToString of the
/// outcome (e.g. "success", "knocked_over"), or "abandoned".
std::string_view OutcomeName(const TrialRecord& trial);

/// What one tick produced.
struct TickResult {
  /// The encoded state packet for `peer`; empty when no valid command has come in yet.
  std::vector<uint8_t> state_packet;
  std::optional<uint64_t> peer;      ///< the sender of the newest valid command
  viewer::ViewerState view;          ///< what the viewer should draw
  uint32_t flags = 0;                ///< StateFlag bits of the state
  std::optional<TrialRecord> trial;  ///< a trial that ended at this tick
  bool finished = false;             ///< the session is over (end requested, nothing pending)
};

/// The session (see the file comment). Not thread-safe: one thread calls Step().
class TeleopSession {
 public:
  /// Builds the world at the first orientation, the robot at its rest configuration. The model
  /// must outlive the session. Throws InputError when `options` is not valid or a rest
  /// configuration is unreachable; creates record_dir when set.
  TeleopSession(const SimulationModel& model, TeleopOptions options);
  ~TeleopSession();
  TeleopSession(const TeleopSession&) = delete;
  TeleopSession& operator=(const TeleopSession&) = delete;

  /// One control tick: takes `datagrams` (any bytes), advances the simulation by 1 / rate_hz
  /// and returns the state. `now` (s, non-decreasing; any origin) measures the operator's
  /// silence. Never throws for anything in the datagrams.
  TickResult Step(std::span<const Datagram> datagrams, double now);

  /// Ends the session as soon as no trial waits for its judgement (the hold after an
  /// end-of-trial press is finished first). An end-of-session packet does the same.
  void RequestEnd();
  /// True once the session is over; later Step() calls only hold the robot.
  bool finished() const;

  const PacketCounters& counters() const;
  const std::vector<TrialRecord>& trials() const;
  const TeleopOptions& options() const;
  /// Physics steps per tick and their length (s).
  int steps_per_tick() const;
  double physics_step() const;
  /// The current orientation, deg, and the 1-based index of the next trial.
  double theta_deg() const;
  /// Measured arm joints (rad), hand joints f0..f15 (rad), object pose, wrist pose X_WH.
  Vector7d arm() const;
  HandVector hand() const;
  Eigen::Isometry3d object_pose() const;
  Eigen::Isometry3d wrist_pose() const;
  /// Commanded arm and hand joints (after the velocity cap), rad.
  const Vector7d& arm_command() const;
  const HandVector& hand_command() const;
  /// The rest configuration of the arm for orientation theta (deg): where every trial starts
  /// (DefaultRestConfiguration, scene/rest_pose.hpp, for the wrist orientation of the
  /// scripted grasp, motion/scripted_grasp.hpp). Throws InputError when the rest pose of the
  /// scene is out of reach.
  static Vector7d RestArm(const RobotModel& robot, const SceneModel& scene, double theta_deg);
  /// The open hand where every trial starts: the scripted grasp's open hand of `robot`
  /// (RobotGraspOf, its robot file's `grasp.open_deg`), rad. Throws RobotGraspOf's InputError.
  static HandVector RestHand(const RobotModel& robot);

  /// The summary (`graspsynth-teleop-session/1`, JSON): options, counters (dropped by reason),
  /// ticks, trials with outcome and file. `end` says why the session ended (e.g.
  /// "end_of_session", "signal"); `wall_s` the session's wall time.
  std::string SummaryJson(const std::string& end, double wall_s) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace graspsynth::teleop
