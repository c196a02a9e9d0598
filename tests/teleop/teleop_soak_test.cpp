// The soak test of the teleoperation session: ten minutes of simulated time at 60 Hz ticks, the
// operator sending at 1 kHz (16 or 17 commands per tick: the scripted grasp at 60 deg, again
// and again) with garbage, duplicates and reordered packets interleaved (one in ten of each
// kind's slots). Every datagram is counted by what it is, the trials keep succeeding, and the
// process's memory stays flat after the first minute.

#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>

#include "teleop/teleop_session.hpp"
#include "tests/teleop/teleop_fixtures.hpp"
#include "tests/utils/simulation_fixtures.hpp"

namespace graspsynth::teleop {
namespace {

using graspsynth::testing::ShippedSimulationModel;

constexpr double kRate = 60.0;
constexpr double kPacketRate = 1000.0;

// resident memory of this process, kB (VmRSS of /proc/self/status).
long ResidentKb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  long kb = 0;
  while (status >> key) {
    if (key == "VmRSS:") {
      status >> kb;
      return kb;
    }
    status.ignore(1 << 12, '\n');
  }
  return -1;
}

// the scripted grasp at 60 deg as the wrist poses and fingers of 60 Hz samples, with the grasp
// and end-of-trial buttons (identity calibration: the sensor pose is the wrist pose).
std::vector<OperatorCommand> TrialCommands() {
  const DemoLog log = graspsynth::testing::ScriptedDemoLog(60.0, kRate);
  std::vector<OperatorCommand> out;
  for (const DemoSample& s : log.samples) {
    OperatorCommand c;
    c.p_TW = s.p_WH;
    c.q_TW = s.q_WH.normalized();
    c.hand_mode = HandMode::kJoints;
    c.fingers = s.f;
    c.buttons = s.event == DemoEvent::kGrasp ? kGraspButton
                : s.event == DemoEvent::kEnd ? kEndTrialButton
                                             : 0;
    out.push_back(c);
  }
  return out;
}

TEST(TeleopSoak, TenMinutesAtOneKilohertzWithGarbageDuplicatesAndReordering) {
  // ten simulated minutes; one under the sanitizers (their allocator keeps freed memory in
  // quarantine, so the memory bound is checked only in the plain build).
  const int minutes = graspsynth::testing::Scaled(10, 1);
  TeleopOptions options;
  options.rate_hz = kRate;
  options.orientations_deg = {60.0};
  TeleopSession session(ShippedSimulationModel(), options);
  const std::vector<OperatorCommand> trial = TrialCommands();

  std::mt19937 rng(17);
  uint64_t sent = 0, garbage = 0, duplicates = 0, reordered = 0, valid = 0;
  uint32_t sequence = 1;
  size_t sample = 0;  // the operator's place in the trial
  long rss_after_first_minute = 0;
  const int ticks = static_cast<int>(minutes * 60 * kRate);
  double packet_clock = 0.0;
  uint64_t judging_ticks = 0;  // the hold before a judgement: commands are not applied
  std::vector<Datagram> in;
  for (int k = 0; k < ticks; ++k) {
    const double now = k / kRate;
    // the packets of this tick: as many as 1 kHz gives, the first with the sample's buttons
    // (a press is one 0 -> 1 change), the others without.
    in.clear();
    std::vector<std::vector<uint8_t>> packets;
    for (; packet_clock < now + 1.0 / kRate; packet_clock += 1.0 / kPacketRate) {
      OperatorCommand c = trial[sample];
      c.sequence = sequence++;
      c.sender_time = packet_clock;
      packets.push_back(EncodeCommand(c));
    }
    valid += packets.size();
    for (size_t j = 0; j < packets.size(); ++j) {
      const uint64_t slot = sent + j;
      if (slot % 10 == 4 && j + 1 < packets.size()) {
        // reordered: the next packet overtakes this one, which then arrives out of order.
        in.push_back({packets[j + 1], 7});
        in.push_back({packets[j], 7});
        ++reordered;
        ++j;
        continue;
      }
      in.push_back({packets[j], 7});
      if (slot % 10 == 7) {  // sent twice
        in.push_back({packets[j], 7});
        ++duplicates;
      }
      if (slot % 10 == 1) {  // garbage: random bytes (never the magic) or a packet cut short
        std::vector<uint8_t> junk(1 + rng() % 300);
        for (uint8_t& b : junk) b = static_cast<uint8_t>(rng());
        if (rng() % 2 == 0)
          junk = std::vector<uint8_t>(packets[j].begin(), packets[j].begin() + rng() % 28);
        if (!junk.empty()) junk[0] = 'X';
        in.push_back({junk, 7});
        ++garbage;
      }
    }
    sent += in.size();
    const TickResult r = session.Step(in, now);
    ASSERT_FALSE(r.state_packet.empty()) << "tick " << k;
    judging_ticks += (r.flags & kJudging) != 0;
    // the operator follows the trial; after a judgement it starts again from the first sample.
    sample = r.trial ? 0 : std::min(sample + 1, trial.size() - 1);
    if (k + 1 == static_cast<int>(60 * kRate)) rss_after_first_minute = ResidentKb();
  }

  const PacketCounters& c = session.counters();
  const auto dropped = [&](DropReason reason) { return c.dropped[static_cast<int>(reason)]; };
  EXPECT_EQ(c.received, sent);
  EXPECT_EQ(c.received, c.accepted + c.dropped_total());
  EXPECT_EQ(c.accepted, valid - reordered);
  EXPECT_EQ(dropped(DropReason::kDuplicate), duplicates);
  EXPECT_EQ(dropped(DropReason::kOutOfOrder), reordered);
  EXPECT_EQ(dropped(DropReason::kBadMagic) + dropped(DropReason::kShort), garbage);
  EXPECT_EQ(c.commands_applied + judging_ticks, static_cast<uint64_t>(ticks));
  EXPECT_GT(garbage, sent / 15);

  // the operator's trials keep succeeding (each takes the trial's length and the 1 s hold).
  const auto& trials = session.trials();
  ASSERT_GE(trials.size(), static_cast<size_t>(minutes * 60 / (trial.size() / kRate + 1.5)));
  for (const TrialRecord& t : trials) EXPECT_TRUE(t.success) << t.index << ": " << t.reason;

#ifndef GRASPSYNTH_SANITIZED
  const long rss_end = ResidentKb();
  ASSERT_GT(rss_after_first_minute, 0);
  // flat: the last nine minutes add less than 8 MB (the trial records are a few hundred bytes).
  EXPECT_LT(rss_end - rss_after_first_minute, 8 * 1024)
      << rss_after_first_minute << " kB after a minute, " << rss_end << " kB at the end";
#endif
}

}  // namespace
}  // namespace graspsynth::teleop
