// The teleoperation loop's cost per control tick (packet in -> state out) and the control rate
// it holds under a packet flood. Figures: benchmarks/README.md, "Teleoperation".
//
// The operator stream is the scripted grasp at theta = 60 deg (motion/scripted_grasp.hpp)
// as 60 Hz commands: reach, approach, close, lift, with the grasp and end-of-trial buttons, so
// that the ticks cover free space, contact and a held object; the stream restarts after each
// trial (the session judges it and resets the world).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <random>
#include <thread>

#include "kinematics/arm_model.hpp"
#include "motion/scripted_grasp.hpp"
#include "teleop/teleop_session.hpp"
#include "teleop/udp_link.hpp"

namespace graspsynth::bench {
namespace {

constexpr double kRate = 60.0;

const SimulationModel& Model() {
  static const SimulationModel model = LoadDefaultSimulationModel();
  return model;
}

// the scripted grasp as operator commands at 60 Hz (identity calibration: X_TS = X_WH).
const std::vector<teleop::OperatorCommand>& ScriptedCommands() {
  static const std::vector<teleop::OperatorCommand> commands = [] {
    const RobotModel& robot = Model().robot();
    ScriptedGraspOptions options;
    options.theta_deg = 60.0;
    const ScriptedGraspResult grasp = BuildScriptedGrasp(robot, Model().scene(), options);
    const JointTrajectory& trajectory = grasp.trajectory;
    const int n = static_cast<int>(trajectory.duration() * kRate);
    const int k_grasp = static_cast<int>(std::lround(trajectory.waypoints.at(2).t * kRate));
    std::vector<teleop::OperatorCommand> out;
    for (int k = 0; k <= n; ++k) {
      const TrajectorySample s = SampleAt(trajectory, k / kRate);
      const Eigen::Isometry3d X_WH = ArmFlangePose(robot.arm, s.arm) * robot.X_FH;
      teleop::OperatorCommand c;
      c.p_TW = X_WH.translation();
      c.q_TW = Eigen::Quaterniond(X_WH.linear());
      c.hand_mode = teleop::HandMode::kJoints;
      c.fingers = s.hand;
      c.buttons = k == k_grasp ? teleop::kGraspButton : k == n ? teleop::kEndTrialButton : 0;
      out.push_back(c);
    }
    return out;
  }();
  return commands;
}

teleop::TeleopOptions SessionOptions() {
  teleop::TeleopOptions options;
  options.rate_hz = kRate;
  options.orientations_deg = {60.0};
  options.end_hold_s = 1.0;
  return options;
}

// bad datagrams of every kind, cycled through by the flood.
std::vector<std::vector<uint8_t>> BadDatagrams() {
  std::mt19937 rng(3);
  std::vector<std::vector<uint8_t>> bad;
  const std::vector<uint8_t> good = teleop::EncodeCommand(ScriptedCommands().front());
  for (int i = 0; i < 64; ++i) {
    std::vector<uint8_t> b = good;
    switch (i % 4) {
      case 0:  // a flipped byte: bad checksum
        b[24 + rng() % 100] ^= 0x5A;
        break;
      case 1:  // random bytes
        for (uint8_t& x : b) x = static_cast<uint8_t>(rng());
        break;
      case 2:  // truncated
        b.resize(rng() % b.size());
        break;
      case 3:  // a valid packet that repeats an old sequence number
        b = teleop::EncodeCommand(ScriptedCommands()[i]);
        break;
    }
    bad.push_back(b);
  }
  return bad;
}

// one tick with the next command of the stream and `flood` bad datagrams beside it.
void TickLoop(benchmark::State& state, int flood) {
  teleop::TeleopSession session(Model(), SessionOptions());
  const std::vector<teleop::OperatorCommand>& commands = ScriptedCommands();
  const std::vector<std::vector<uint8_t>> bad = BadDatagrams();
  std::vector<teleop::Datagram> in;
  uint32_t sequence = 1000;
  size_t k = 0;
  uint64_t ticks = 0;
  double t = 0.0;
  for (auto _ : state) {
    in.clear();
    for (int i = 0; i < flood; ++i) in.push_back({bad[i % bad.size()], 1});
    teleop::OperatorCommand c = commands[k];
    c.sequence = sequence++;
    in.push_back({teleop::EncodeCommand(c), 1});
    const teleop::TickResult r = session.Step(in, t);
    benchmark::DoNotOptimize(r.state_packet.data());
    k = r.trial ? 0 : (k + 1) % commands.size();  // a judged trial: the operator starts over
    t += 1.0 / kRate;
    ++ticks;
  }
  state.counters["datagrams/tick"] = flood + 1;
  state.counters["trials"] = static_cast<double>(session.trials().size());
  state.counters["successes"] =
      static_cast<double>(std::count_if(session.trials().begin(), session.trials().end(),
                                        [](const teleop::TrialRecord& r) { return r.success; }));
}

// processing per tick (decode, IK, velocity caps, 5 physics steps, state packet) over the
// scripted trial, cycled: free space, contact and the held object in their proportions.
void BM_TeleopTick(benchmark::State& state) { TickLoop(state, 0); }
BENCHMARK(BM_TeleopTick)->Unit(benchmark::kMicrosecond)->Iterations(2000)->Repetitions(3);

// the same with a flood of bad datagrams in every tick (counted and dropped).
void BM_TeleopTickUnderFlood(benchmark::State& state) {
  TickLoop(state, static_cast<int>(state.range(0)));
}
BENCHMARK(BM_TeleopTickUnderFlood)
    ->Arg(100)
    ->Arg(1000)
    ->Arg(4096)
    ->Unit(benchmark::kMicrosecond)
    ->Iterations(1000);

// The real loop over loopback UDP for 5 s of wall time: a flood thread sends bad datagrams as
// fast as it can (and the operator stream at 60 Hz); the control loop receives (at most 4096 a
// tick), steps and answers at 60 Hz. Reported: ticks per wall second, processing per tick (mean,
// max; receive + Step + send), datagrams handled per second, late ticks.
void BM_TeleopLoopUnderUdpFlood(benchmark::State& state) {
  const bool flood = state.range(0) != 0;
  for (auto _ : state) {
    teleop::TeleopSession session(Model(), SessionOptions());
    teleop::UdpLink server;
    const uint64_t to = teleop::ParsePeer("127.0.0.1", server.port());
    std::atomic<bool> stop{false};
    std::atomic<uint64_t> flood_sent{0};
    std::thread flooder([&] {
      if (!flood) return;
      teleop::UdpLink link;
      const std::vector<std::vector<uint8_t>> bad = BadDatagrams();
      size_t i = 0;
      while (!stop.load(std::memory_order_relaxed)) {
        link.Send(bad[i++ % bad.size()], to);
        flood_sent.fetch_add(1, std::memory_order_relaxed);
      }
    });
    std::thread operator_stream([&] {
      teleop::UdpLink link;
      const auto start = std::chrono::steady_clock::now();
      uint32_t sequence = 0;
      for (size_t k = 0; !stop.load(); ++k) {
        teleop::OperatorCommand c = ScriptedCommands()[k % ScriptedCommands().size()];
        c.sequence = sequence++;
        link.Send(teleop::EncodeCommand(c), to);
        std::this_thread::sleep_until(start + std::chrono::microseconds(16667 * (k + 1)));
      }
    });
    using Clock = std::chrono::steady_clock;
    const auto tick = std::chrono::microseconds(16667);
    const Clock::time_point start = Clock::now();
    Clock::time_point next = start;
    uint64_t ticks = 0, late = 0, received = 0;
    double busy = 0.0, busy_max = 0.0;
    std::vector<teleop::Datagram> in;
    while (Clock::now() - start < std::chrono::seconds(5)) {
      const Clock::time_point t0 = Clock::now();
      in.clear();
      received += server.Receive(&in);
      const teleop::TickResult r =
          session.Step(in, std::chrono::duration<double>(t0 - start).count());
      if (!r.state_packet.empty()) server.Send(r.state_packet, *r.peer);
      const double b = std::chrono::duration<double>(Clock::now() - t0).count();
      busy += b;
      busy_max = std::max(busy_max, b);
      ++ticks;
      next += tick;
      if (next < Clock::now()) {
        ++late;
        next = Clock::now();
      }
      std::this_thread::sleep_until(next);
    }
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();
    stop = true;
    flooder.join();
    operator_stream.join();
    state.counters["tick_hz"] = ticks / wall;
    state.counters["busy_ms_mean"] = busy / ticks * 1e3;
    state.counters["busy_ms_max"] = busy_max * 1e3;
    state.counters["late_ticks"] = static_cast<double>(late);
    state.counters["datagrams_in/s"] = received / wall;
    state.counters["flood_sent/s"] = flood_sent.load() / wall;
    state.counters["applied"] = static_cast<double>(session.counters().commands_applied);
    state.counters["dropped"] = static_cast<double>(session.counters().dropped_total());
  }
}
BENCHMARK(BM_TeleopLoopUnderUdpFlood)
    ->Arg(0)
    ->Arg(1)
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace graspsynth::bench

BENCHMARK_MAIN();
