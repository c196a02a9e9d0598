#include "teleop/teleop_session.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>

#include "common/errors.hpp"
#include "common/format.hpp"
#include "common/valid_options.hpp"
#include "kinematics/arm_ik.hpp"
#include "kinematics/pose_math.hpp"
#include "motion/joint_space.hpp"
#include "motion/scripted_grasp.hpp"
#include "scene/rest_pose.hpp"
#include "simulation/simulation_data.hpp"
#include "simulation/trial_judge.hpp"

namespace graspsynth::teleop {
namespace {

enum class Phase {
  kWaiting,  // world reset, no command applied since: no trial open
  kActive,   // a trial is open and recorded
  kJudging,  // the hold after the end-of-trial button
};

}  // namespace

std::string_view OutcomeName(const TrialRecord& trial) {
  return trial.outcome ? ToString(*trial.outcome) : std::string_view("abandoned");
}

uint64_t PacketCounters::dropped_total() const {
  uint64_t total = 0;
  for (uint64_t n : dropped) total += n;
  return total;
}

bool TeleopOptions::IsValid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  if (!(std::isfinite(rate_hz) && rate_hz >= 1.0 && rate_hz <= 1000.0)) {
    return fail("rate_hz (Hz, in [1, 1000]) = " + std::to_string(rate_hz));
  }
  if (!(std::isfinite(max_physics_step) && max_physics_step > 0.0 && max_physics_step <= 0.02)) {
    return fail("max_physics_step (s, in (0, 0.02]) = " + std::to_string(max_physics_step));
  }
  if (!(std::isfinite(timeout_s) && timeout_s > 0.0)) {
    return fail("timeout_s (s, > 0) = " + std::to_string(timeout_s));
  }
  if (!(std::isfinite(end_hold_s) && end_hold_s >= 0.0 && end_hold_s <= 60.0)) {
    return fail("end_hold_s (s, in [0, 60]) = " + std::to_string(end_hold_s));
  }
  std::string judge_why;
  if (!judge.IsValid(&judge_why)) return fail("judge." + judge_why);
  if (orientations_deg.empty()) return fail("orientations_deg is empty");
  for (double theta : orientations_deg) {
    if (!(std::isfinite(theta) && std::abs(theta) <= 360.0)) {
      return fail("orientation (deg, in [-360, 360]) = " + std::to_string(theta));
    }
  }
  return true;
}

struct TeleopSession::Impl {
  const SimulationModel& model;
  TeleopOptions options;
  GloveMap glove;
  int steps = 1;                    // physics steps per tick
  double h = 0.0;                   // physics step, s
  double tick = 0.0;                // s
  std::vector<Vector7d> rest_arms;  // per orientation
  HandVector rest_hand;             // the robot's open hand (RestHand)

  size_t orientation = 0;
  std::unique_ptr<SimulationData> world;
  bool kinematic = true;  // free space: no contact detail yet
  Vector7d q_cmd, q_goal, q_ik;
  HandVector f_cmd, f_goal;

  SequenceFilter sequence;
  uint8_t previous_buttons = 0;
  std::optional<double> last_command_time;
  std::optional<uint64_t> peer;
  uint32_t state_sequence = 0;
  bool out_of_reach = false;

  Phase phase = Phase::kWaiting;
  std::vector<DemoSample> samples;
  std::optional<size_t> grasp_sample;
  double trial_start = 0.0;
  double judge_at = 0.0;
  TrialWatch watch;                     // the judgement's figures of the open trial
  std::optional<TrialVerdict> decided;  // the first early verdict of the open trial

  bool end_requested = false;
  bool finished = false;
  bool last_success = false;
  PacketCounters counters;
  std::vector<TrialRecord> trials;
  uint64_t ticks = 0;
  uint64_t ticks_holding = 0;
  uint64_t ticks_out_of_reach = 0;
  double simulated = 0.0;

  Impl(const SimulationModel& m, TeleopOptions o) : model(m), options(std::move(o)) {
    RequireValid(options, "invalid teleoperation option");
    if (options.object_xy) model.scene().CheckOnTable(*options.object_xy);
    glove = options.glove_map ? *options.glove_map : GloveMap::Default(model.robot().hand);
    tick = 1.0 / options.rate_hz;
    steps = std::max(1, static_cast<int>(std::ceil(tick / options.max_physics_step - 1e-9)));
    h = tick / steps;
    rest_hand = RestHand(model.robot());
    for (double theta : options.orientations_deg) {
      rest_arms.push_back(RestArm(model.robot(), model.scene(), theta));
    }
    if (!options.record_dir.empty()) {
      std::error_code ec;
      std::filesystem::create_directories(options.record_dir, ec);
      if (ec) {
        throw InputError("record folder " + options.record_dir.string() +
                         " cannot be created: " + ec.message());
      }
    }
    Reset();
  }

  double theta_deg() const { return options.orientations_deg[orientation]; }

  void Reset() {
    WorldOptions world_options;
    world_options.time_step = h;
    world_options.arm_mode = ArmMode::kKinematic;
    world_options.theta = Radians(theta_deg());
    world_options.object_xy = options.object_xy;
    const Vector7d& rest = rest_arms[orientation];
    world = std::make_unique<SimulationData>(model, world_options, rest, rest_hand);
    kinematic = true;
    q_cmd = q_goal = q_ik = rest;
    f_cmd = f_goal = rest_hand;
    phase = Phase::kWaiting;
    samples.clear();
    grasp_sample.reset();
    out_of_reach = false;
    watch = StartTrialWatch(world->object_pose());
    decided.reset();
  }

  // a trial ends: judged (or abandoned: std::nullopt), written when it can be, listed.
  TrialRecord EndTrial(std::optional<TrialOutcome> outcome, const std::string& reason) {
    TrialRecord r;
    r.index = static_cast<int>(trials.size()) + 1;
    r.theta_deg = theta_deg();
    r.outcome = outcome;
    r.success = outcome == TrialOutcome::kSuccess;
    r.reason = reason;
    const Eigen::Vector3d p_WO_rest = watch.X_WO_rest.translation();
    r.lift_m =
        world && world->IsFinite() ? world->object_pose().translation().z() - p_WO_rest.z() : 0.0;
    r.duration_s = samples.empty() ? 0.0 : samples.back().t;
    r.samples = samples.size();
    r.has_grasp = grasp_sample.has_value();
    if (options.record_dir.empty()) {
      r.not_written = "not recording";
    } else if (!outcome || *outcome == TrialOutcome::kUnstable) {
      r.not_written = "the trial was " + std::string(OutcomeName(r));
    } else if (!grasp_sample) {
      r.not_written = "the grasp button was never pressed (a v1 log needs one grasp event)";
    } else if (*grasp_sample + 1 == samples.size()) {
      r.not_written = "the grasp and the end fell on the same sample";
    } else {
      WriteTrialLog(p_WO_rest, &r);
    }
    last_success = r.success;
    trials.push_back(r);
    return r;
  }

  // the v1 log of a judged trial with a grasp mark; r->file or r->not_written tells how it went.
  void WriteTrialLog(const Eigen::Vector3d& p_WO_rest, TrialRecord* r) const {
    DemoLog log;
    char name[64];
    std::snprintf(name, sizeof(name), "trial_%03d_theta%g.csv", r->index, r->theta_deg);
    log.source = (options.record_dir / name).string();
    log.metadata.theta_deg = r->theta_deg;
    log.metadata.object_position = p_WO_rest;
    log.metadata.trial = std::to_string(r->index);
    if (!options.operator_name.empty()) log.metadata.operator_name = options.operator_name;
    log.metadata.sample_rate_hz = options.rate_hz;
    log.metadata.extra = {{"outcome", std::string(OutcomeName(*r))},
                          {"recorded_by", "graspsynth teleop"}};
    log.samples = samples;
    log.samples.back().event = DemoEvent::kEnd;
    try {
      WriteDemoLog(log.source, log);
      r->file = log.source;
    } catch (const std::exception& e) {
      r->not_written = e.what();
    }
  }

  // the judgement after the hold: the first early verdict of the trial, else the end state.
  TrialRecord Judge() {
    const TrialVerdict verdict =
        decided ? *decided : JudgeTrial(*world, watch, options.end_hold_s, options.judge);
    return EndTrial(verdict.outcome, verdict.reason);
  }

  // the newest valid command of the tick sets the targets.
  void Apply(const OperatorCommand& command) {
    const RobotModel& robot = model.robot();
    Eigen::Isometry3d X_TS = PoseFrom(command.p_TW, command.q_TW.normalized());
    const Eigen::Isometry3d X_WH = options.calibration.WristInWorld(X_TS);
    const std::optional<Vector7d> q =
        SolveWristPose(robot, X_WH, BranchOf(robot.arm, q_ik), ArmAngleOf(robot.arm, q_ik), q_ik);
    out_of_reach = !q.has_value();
    if (q) {
      q_ik = *q;
      q_goal = *q;
    }
    if (command.hand_mode == HandMode::kGlove) {
      f_goal = GloveToJoints(glove, robot.hand, command.fingers.head<kGloveSensors>());
    } else {
      f_goal = command.fingers.cwiseMax(robot.hand.lower()).cwiseMin(robot.hand.upper());
    }
  }

  // one tick of physics from the previous commands to the new ones. An instability ends it
  // with its verdict; a joint limit or a collision during a trial is kept for the judgement.
  std::optional<TrialVerdict> Simulate(const Vector7d& q_from, const HandVector& f_from) {
    const Vector7d dq = q_cmd - q_from;
    const HandVector df = f_cmd - f_from;
    for (int k = 0; k < steps; ++k) {
      const double a = static_cast<double>(k + 1) / steps;
      world->SetArmCommand(ServoMode::kPosition, q_from + a * dq, dq / tick);
      world->SetHandCommand(ServoMode::kPosition, f_from + a * df);
      try {
        StepTrialWorld(world.get(), &kinematic);
      } catch (const std::exception& e) {
        return OdeFailureVerdict(world->time(), e.what());
      }
      std::optional<TrialVerdict> verdict = EarlyVerdict(*world, model.robot().arm, options.judge);
      if (verdict && verdict->outcome == TrialOutcome::kUnstable) return verdict;
      if (phase == Phase::kWaiting) continue;
      if (verdict && !decided) decided = std::move(verdict);
      WatchStep(*world, options.judge, &watch);
    }
    return std::nullopt;
  }

  TickResult MakeResult(double now, uint32_t flags) {
    TickResult result;
    result.flags = flags;
    RobotStateMessage state;
    state.sender_time = now;
    state.arm = world->arm_positions();
    state.hand = world->hand_positions();
    const Eigen::Isometry3d X_WO = world->object_pose();
    state.p_WO = X_WO.translation();
    state.q_WO = Eigen::Quaterniond(X_WO.linear());
    state.theta_deg = theta_deg();
    state.trial = static_cast<uint32_t>(trials.size() + 1);
    state.flags = flags;
    if (peer) {
      state.sequence = state_sequence++;
      result.state_packet = EncodeState(state, options.key ? &*options.key : nullptr);
      result.peer = peer;
      ++counters.states_sent;
    }
    result.view.t = simulated;
    result.view.arm = state.arm;
    result.view.hand = state.hand;
    result.view.X_WO = X_WO;
    std::string text = Format("theta %.1f deg | trial %.0f", theta_deg(), trials.size() + 1.0);
    if (phase == Phase::kActive)
      text += grasp_sample ? " | recording, grasp marked" : " | recording";
    if (phase == Phase::kJudging) text += " | judging the trial";
    if (phase == Phase::kWaiting) text += " | waiting for the operator";
    if (flags & kHoldingStill) text += " | no operator packets: holding still";
    if (flags & kOutOfReach) text += " | wrist target out of reach: holding";
    if (!trials.empty()) {
      text += " | last trial: " + std::string(OutcomeName(trials.back()));
    }
    result.view.text = text;
    result.finished = finished;
    return result;
  }

  // the valid commands of a tick: the newest, and the buttons pressed by any of them.
  struct Received {
    std::optional<OperatorCommand> newest;
    uint8_t pressed = 0;
  };

  // 1. decodes and checks every datagram; counts the drops.
  Received Receive(std::span<const Datagram> datagrams, double now) {
    Received in;
    for (const Datagram& d : datagrams) {
      ++counters.received;
      const DecodeResult decoded = Decode(d.bytes, options.key ? &*options.key : nullptr);
      if (!decoded.packet) {
        ++counters.dropped[static_cast<int>(decoded.reason)];
        continue;
      }
      if (decoded.packet->kind == PacketKind::kState) {
        ++counters.dropped[static_cast<int>(DropReason::kUnknownKind)];
        continue;
      }
      if (const auto reason = sequence.Check(decoded.packet->sequence)) {
        ++counters.dropped[static_cast<int>(*reason)];
        continue;
      }
      ++counters.accepted;
      if (decoded.packet->kind == PacketKind::kEndOfSession) {
        end_requested = true;
        continue;
      }
      const OperatorCommand& c = decoded.packet->command;
      in.pressed |= static_cast<uint8_t>(c.buttons & ~previous_buttons);
      previous_buttons = c.buttons;
      in.newest = c;
      peer = d.peer;
      last_command_time = now;
      if (phase == Phase::kJudging || finished) ++counters.ignored_while_judging;
    }
    return in;
  }

  // 2. buttons: next orientation first (it resets the world), then the trial's own. True when
  // the grasp button marks this tick's sample.
  bool Buttons(Received* in, std::optional<TrialRecord>* ended) {
    if (phase != Phase::kJudging && (in->pressed & kNextOrientationButton)) {
      if (phase == Phase::kActive)
        *ended = EndTrial(std::nullopt, "the next orientation was chosen");
      orientation = (orientation + 1) % options.orientations_deg.size();
      Reset();
      in->newest.reset();  // the command that pressed it must not start the new trial
      in->pressed = 0;
    }
    if (in->newest && phase != Phase::kJudging) {
      if (phase == Phase::kWaiting) {
        phase = Phase::kActive;
        trial_start = world->time();
      }
      Apply(*in->newest);
      ++counters.commands_applied;
    }
    const bool grasp_now = phase == Phase::kActive && (in->pressed & kGraspButton);
    if (phase == Phase::kActive && (in->pressed & kEndTrialButton)) {
      phase = Phase::kJudging;
      judge_at = world->time() + options.end_hold_s;
    }
    return grasp_now;
  }

  // 3. silence or judging freezes the commands; else they move toward the targets, capped.
  uint32_t MoveCommands(double now) {
    const bool silent = !last_command_time || now - *last_command_time > options.timeout_s;
    uint32_t flags = 0;
    if (silent) {
      flags |= kHoldingStill;
      ++ticks_holding;
    }
    if (silent || phase == Phase::kJudging) {
      q_goal = q_cmd;
      f_goal = f_cmd;
    }
    if (out_of_reach) {
      flags |= kOutOfReach;
      ++ticks_out_of_reach;
    }
    const Vector7d dq_max = model.robot().arm.max_velocity() * tick;
    const HandVector df_max = model.robot().hand.max_velocity() * tick;
    q_cmd += (q_goal - q_cmd).cwiseMax(-dq_max).cwiseMin(dq_max);
    f_cmd += (f_goal - f_cmd).cwiseMax(-df_max).cwiseMin(df_max);
    return flags;
  }

  // 5. the sample of this tick, marked as the grasp when `grasp_now`.
  void RecordSample(bool grasp_now) {
    DemoSample s;
    s.t = world->time() - trial_start;
    const Eigen::Isometry3d X_WH = world->wrist_pose();
    s.p_WH = X_WH.translation();
    s.q_WH = Eigen::Quaterniond(X_WH.linear());
    s.f = f_cmd;
    s.p_WO = world->object_pose().translation();
    if (grasp_now) {
      if (grasp_sample) samples[*grasp_sample].event = DemoEvent::kNone;
      grasp_sample = samples.size();
      s.event = DemoEvent::kGrasp;
    }
    samples.push_back(s);
  }

  TickResult Step(std::span<const Datagram> datagrams, double now) {
    Received in = Receive(datagrams, now);
    if (finished) return MakeResult(now, kHoldingStill);
    ++ticks;
    std::optional<TrialRecord> ended;
    const bool grasp_now = Buttons(&in, &ended);
    const Vector7d q_from = q_cmd;
    const HandVector f_from = f_cmd;
    uint32_t flags = MoveCommands(now);

    // 4. physics; an instability ends the trial and resets the world.
    const std::optional<TrialVerdict> unstable = Simulate(q_from, f_from);
    simulated += tick;
    if (unstable) {
      if (phase != Phase::kWaiting) ended = EndTrial(unstable->outcome, unstable->reason);
      Reset();
    } else if (phase != Phase::kWaiting) {
      RecordSample(grasp_now);
      // 6. the judgement after the hold.
      if (phase == Phase::kJudging && world->time() >= judge_at - 1e-9) {
        ended = Judge();
        Reset();
      }
    }
    if (phase == Phase::kActive) flags |= kRecording;
    if (phase == Phase::kJudging) flags |= kJudging;
    if (last_success) flags |= kLastTrialSucceeded;

    if (end_requested && phase != Phase::kJudging) {
      if (phase == Phase::kActive) ended = EndTrial(std::nullopt, "the session ended first");
      phase = Phase::kWaiting;
      finished = true;
    }
    TickResult result = MakeResult(now, flags);
    result.trial = ended;
    return result;
  }
};

TeleopSession::TeleopSession(const SimulationModel& model, TeleopOptions options)
    : impl_(std::make_unique<Impl>(model, std::move(options))) {}
TeleopSession::~TeleopSession() = default;

TickResult TeleopSession::Step(std::span<const Datagram> datagrams, double now) {
  return impl_->Step(datagrams, now);
}
void TeleopSession::RequestEnd() { impl_->end_requested = true; }
bool TeleopSession::finished() const { return impl_->finished; }
const PacketCounters& TeleopSession::counters() const { return impl_->counters; }
const std::vector<TrialRecord>& TeleopSession::trials() const { return impl_->trials; }
const TeleopOptions& TeleopSession::options() const { return impl_->options; }
int TeleopSession::steps_per_tick() const { return impl_->steps; }
double TeleopSession::physics_step() const { return impl_->h; }
double TeleopSession::theta_deg() const { return impl_->theta_deg(); }
Vector7d TeleopSession::arm() const { return impl_->world->arm_positions(); }
HandVector TeleopSession::hand() const { return impl_->world->hand_positions(); }
Eigen::Isometry3d TeleopSession::object_pose() const { return impl_->world->object_pose(); }
Eigen::Isometry3d TeleopSession::wrist_pose() const { return impl_->world->wrist_pose(); }
const Vector7d& TeleopSession::arm_command() const { return impl_->q_cmd; }
const HandVector& TeleopSession::hand_command() const { return impl_->f_cmd; }

Vector7d TeleopSession::RestArm(const RobotModel& robot, const SceneModel& scene,
                                double theta_deg) {
  ScriptedGraspOptions grasp;
  grasp.theta_deg = theta_deg;
  const Eigen::Isometry3d X_WH = GraspWristPose(robot, scene, grasp);
  return DefaultRestConfiguration(robot, scene, X_WH.linear());
}

HandVector TeleopSession::RestHand(const RobotModel& robot) { return RobotGraspOf(robot).open; }

std::string TeleopSession::SummaryJson(const std::string& end, double wall_s) const {
  using nlohmann::json;
  const Impl& s = *impl_;
  json dropped = json::object();
  for (int i = 0; i < kDropReasonCount; ++i) {
    dropped[std::string(ToString(static_cast<DropReason>(i)))] = s.counters.dropped[i];
  }
  json trials = json::array();
  int successes = 0;
  for (const TrialRecord& t : s.trials) {
    successes += t.success ? 1 : 0;
    trials.push_back({{"index", t.index},
                      {"theta_deg", t.theta_deg},
                      {"outcome", OutcomeName(t)},
                      {"success", t.success},
                      {"reason", t.reason},
                      {"lift_m", t.lift_m},
                      {"duration_s", t.duration_s},
                      {"samples", t.samples},
                      {"grasp_marked", t.has_grasp},
                      {"file", t.file.empty() ? json(nullptr) : json(t.file.string())},
                      {"not_written", t.not_written}});
  }
  const json doc = {
      {"format", kTeleopSessionFormat},
      {"end", end},
      {"wall_s", wall_s},
      {"rate_hz", s.options.rate_hz},
      {"physics_step_s", s.h},
      {"steps_per_tick", s.steps},
      {"timeout_s", s.options.timeout_s},
      {"end_hold_s", s.options.end_hold_s},
      {"orientations_deg", s.options.orientations_deg},
      {"authenticated", s.options.key.has_value()},
      {"record_dir",
       s.options.record_dir.empty() ? json(nullptr) : json(s.options.record_dir.string())},
      {"ticks", s.ticks},
      {"simulated_s", s.simulated},
      {"ticks_holding_still", s.ticks_holding},
      {"ticks_out_of_reach", s.ticks_out_of_reach},
      {"packets",
       {{"received", s.counters.received},
        {"accepted", s.counters.accepted},
        {"commands_applied", s.counters.commands_applied},
        {"ignored_while_judging", s.counters.ignored_while_judging},
        {"dropped_total", s.counters.dropped_total()},
        {"dropped", dropped},
        {"states_sent", s.counters.states_sent}}},
      {"trials", trials},
      {"successes", successes}};
  return doc.dump(2) + "\n";
}

}  // namespace graspsynth::teleop
