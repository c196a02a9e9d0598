#include "teleop/teleop_session.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>

#include "common/errors.hpp"
#include "kinematics/arm_model.hpp"
#include "learning_data/segmentation.hpp"
#include "tests/teleop/teleop_fixtures.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::teleop {
namespace {

using graspsynth::testing::JointCommand;
using graspsynth::testing::ShippedSimulationModel;

constexpr double kTick = 1.0 / 60.0;

TeleopOptions SixtyDegrees() {
  TeleopOptions o;
  o.orientations_deg = {60.0};
  return o;
}

const RobotModel& Robot() { return ShippedSimulationModel().robot(); }

// the wrist pose of the rest configuration at 60 deg, moved by `offset` (world, m).
Eigen::Isometry3d RestWrist(const Eigen::Vector3d& offset = Eigen::Vector3d::Zero()) {
  const Vector7d q = TeleopSession::RestArm(Robot(), ShippedSimulationModel().scene(), 60.0);
  Eigen::Isometry3d X_WH = ArmFlangePose(Robot().arm, q) * Robot().X_FH;
  X_WH.translation() += offset;
  return X_WH;
}

Datagram Wrap(std::vector<uint8_t> bytes, uint64_t peer = 7) { return {std::move(bytes), peer}; }

// re-seals modified bytes with a valid checksum.
std::vector<uint8_t> Reseal(std::vector<uint8_t> bytes) {
  bytes.resize(bytes.size() - kCrcBytes);
  const uint32_t crc = Crc32(bytes);
  const auto* p = reinterpret_cast<const uint8_t*>(&crc);
  bytes.insert(bytes.end(), p, p + 4);
  return bytes;
}

std::filesystem::path TempDir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("graspsynth_teleop_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  return dir;
}

TEST(TeleopOptions, RejectsBadValues) {
  std::string why;
  EXPECT_TRUE(TeleopOptions{}.IsValid(&why)) << why;
  TeleopOptions o;
  o.rate_hz = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("rate_hz"), std::string::npos);
  o = {};
  o.orientations_deg.clear();
  EXPECT_FALSE(o.IsValid(&why));
  o = {};
  o.timeout_s = NAN;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("timeout_s"), std::string::npos);
  EXPECT_THROW(TeleopSession session(ShippedSimulationModel(), o), InputError);
  o = {};
  o.judge.lift_threshold = -0.05;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("judge.lift_threshold"), std::string::npos) << why;
}

// A scene that puts the rest pose out of the arm's reach is a clear error at the start of the
// session, naming the scene (it once aborted in an invariant check).
TEST(TeleopSession, AnUnreachableRestPoseIsAnInputErrorNamingTheScene) {
  SceneModel scene = ShippedSimulationModel().scene();
  scene.source = "far_table.json";
  scene.table.top_z += 2.0;
  const SimulationModel far(ShippedSimulationModel().robot(), scene);
  GS_EXPECT_THROW_WITH(TeleopSession(far, SixtyDegrees()), InputError, "scene far_table.json",
                       "rest pose is out of reach");
}

TEST(TeleopSession, PutsTheObjectAtTheAskedPlacementAndRefusesOneOffTheTable) {
  TeleopOptions options = SixtyDegrees();
  options.object_xy = Eigen::Vector2d(-0.30, 0.90);
  const TeleopSession session(ShippedSimulationModel(), options);
  const Eigen::Isometry3d X_WO = session.object_pose();
  EXPECT_NEAR(X_WO.translation().x(), -0.30, 1e-3);
  EXPECT_NEAR(X_WO.translation().y(), 0.90, 1e-3);
  const Eigen::Isometry3d expected = ShippedSimulationModel().scene().ObjectPose(
      Placement{60.0 * M_PI / 180.0, options.object_xy});
  EXPECT_LT((X_WO.linear() - expected.linear()).norm(), 1e-6);
  options.object_xy = Eigen::Vector2d(3.0, 0.9);
  GS_EXPECT_THROW_WITH(TeleopSession(ShippedSimulationModel(), options), InputError,
                       "(3, 0.9) m is not on the table");
}

TEST(TeleopSession, SplitsTheTickIntoEqualPhysicsSteps) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  EXPECT_EQ(session.steps_per_tick(), 5);
  EXPECT_NEAR(session.physics_step() * session.steps_per_tick(), kTick, 1e-12);
  EXPECT_LE(session.physics_step(), 0.004);
}

TEST(TeleopSession, HoldsStillBeforeTheFirstCommandAndSendsNothing) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  const Vector7d q0 = session.arm();
  TickResult r;
  for (int k = 0; k < 30; ++k) r = session.Step({}, k * kTick);
  EXPECT_TRUE(r.flags & kHoldingStill);
  EXPECT_TRUE(r.state_packet.empty());
  EXPECT_FALSE(r.peer);
  EXPECT_LT((session.arm() - q0).cwiseAbs().maxCoeff(), 1e-9);
}

// every kind of bad packet in every tick, next to the operator's stream: each is counted by its
// reason, none is applied, and the robot still reaches the operator's target.
TEST(TeleopSession, DropsBadPacketsByReasonWhileTheRobotStaysControllable) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  const Eigen::Isometry3d target = RestWrist(Eigen::Vector3d(0.06, -0.04, -0.05));
  const HandVector f = TeleopSession::RestHand(ShippedSimulationModel().robot());
  std::mt19937 rng(5);
  const int ticks = 90;
  uint32_t seq = 100;
  std::vector<uint8_t> previous;
  TickResult r;
  for (int k = 0; k < ticks; ++k) {
    std::vector<Datagram> in;
    const std::vector<uint8_t> good = EncodeCommand(JointCommand(seq, target, f));
    // a wild pose with a bad checksum, then one with a NaN (resealed), then garbage.
    OperatorCommand wild = JointCommand(seq + 1, RestWrist(Eigen::Vector3d(0, 0, -2)), f);
    std::vector<uint8_t> bad_crc = EncodeCommand(wild);
    bad_crc[30] ^= 0xFF;
    in.push_back(Wrap(bad_crc));
    wild.p_TW.x() = NAN;
    in.push_back(Wrap(EncodeCommand(wild)));
    in.push_back(Wrap(std::vector<uint8_t>(good.begin(), good.begin() + 10)));  // short
    std::vector<uint8_t> magic = good;
    magic[0] = 'X';
    in.push_back(Wrap(magic));
    std::vector<uint8_t> version = good;
    version[4] = 9;
    in.push_back(Wrap(Reseal(version)));
    std::vector<uint8_t> kind = good;
    kind[6] = 77;
    in.push_back(Wrap(Reseal(kind)));
    std::vector<uint8_t> length = good;
    length.push_back(0);
    in.push_back(Wrap(length));
    std::vector<uint8_t> garbage(200);
    for (uint8_t& b : garbage) b = static_cast<uint8_t>(rng());
    in.push_back(Wrap(garbage));
    RobotStateMessage state;  // a state sent to the server: not a kind it takes
    in.push_back(Wrap(EncodeState(state)));
    in.push_back(Wrap(good));
    in.push_back(Wrap(good));                             // duplicate
    if (!previous.empty()) in.push_back(Wrap(previous));  // older than the last applied
    previous = good;
    seq += 2;
    r = session.Step(in, k * kTick);
    ASSERT_FALSE(r.state_packet.empty());
  }
  const PacketCounters& c = session.counters();
  const auto dropped = [&](DropReason reason) { return c.dropped[static_cast<int>(reason)]; };
  EXPECT_EQ(c.accepted, static_cast<uint64_t>(ticks));
  EXPECT_EQ(c.commands_applied, static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kBadChecksum), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kBadValue), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kShort), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kBadVersion), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kUnknownKind), 2u * ticks);  // unknown kind + robot states
  EXPECT_EQ(dropped(DropReason::kBadLength), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kDuplicate), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kOutOfOrder), static_cast<uint64_t>(ticks - 1));
  // random bytes fail the magic (or, rarely, something later).
  EXPECT_GE(dropped(DropReason::kBadMagic), static_cast<uint64_t>(ticks));
  EXPECT_EQ(c.received, c.accepted + c.dropped_total());
  EXPECT_EQ(c.states_sent, static_cast<uint64_t>(ticks));
  // the robot went where the valid packets said.
  EXPECT_LT((session.wrist_pose().translation() - target.translation()).norm(), 2e-3);
  EXPECT_EQ(*r.peer, 7u);
  const DecodeResult state = Decode(r.state_packet);
  ASSERT_TRUE(state.packet);
  EXPECT_EQ(state.packet->kind, PacketKind::kState);
  EXPECT_EQ(state.packet->state.sequence, static_cast<uint32_t>(ticks - 1));
  EXPECT_EQ(state.packet->state.theta_deg, 60.0);
  EXPECT_TRUE((state.packet->state.arm - session.arm()).isZero(0.0));
}

// whatever bytes come in, the session neither throws nor loses its state.
TEST(TeleopSession, SurvivesAFloodOfMutatedPackets) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  std::mt19937 rng(11);
  const std::vector<uint8_t> base = EncodeCommand(
      JointCommand(1, RestWrist(), TeleopSession::RestHand(ShippedSimulationModel().robot())));
  const int ticks = graspsynth::testing::Scaled(30, 5);
  for (int k = 0; k < ticks; ++k) {
    std::vector<Datagram> in;
    for (int i = 0; i < 500; ++i) {
      std::vector<uint8_t> b = base;
      const int flips = 1 + static_cast<int>(rng() % 4);
      for (int j = 0; j < flips; ++j) b[rng() % b.size()] = static_cast<uint8_t>(rng());
      if (rng() % 2) b = Reseal(b);  // some pass the checksum and reach the value checks
      if (rng() % 7 == 0) b.resize(rng() % b.size());
      in.push_back(Wrap(std::move(b), rng()));
    }
    ASSERT_NO_THROW(session.Step(in, k * kTick));
  }
  EXPECT_EQ(session.counters().received, 500u * ticks);
  EXPECT_TRUE(session.arm().allFinite());
  EXPECT_TRUE(session.object_pose().translation().allFinite());
  const Vector7d q = session.arm();
  EXPECT_TRUE((q.array() >= Robot().arm.lower().array() - 1e-9).all());
  EXPECT_TRUE((q.array() <= Robot().arm.upper().array() + 1e-9).all());
}

// the operator goes silent during a long move: after the timeout the robot stops where it is.
TEST(TeleopSession, AStallLongerThanTheTimeoutHoldsTheRobotStill) {
  TeleopOptions options = SixtyDegrees();
  options.timeout_s = 0.2;
  TeleopSession session(ShippedSimulationModel(), options);
  const Eigen::Isometry3d far = RestWrist(Eigen::Vector3d(-0.2, 0.2, 0.2));
  uint32_t seq = 0;
  int k = 0;
  for (; k < 3; ++k) {
    const Datagram d = Wrap(EncodeCommand(
        JointCommand(seq++, far, TeleopSession::RestHand(ShippedSimulationModel().robot()))));
    session.Step({&d, 1}, k * kTick);
  }
  // silence from t = 2 ticks on: the robot goes on toward the target for 0.2 s, then holds.
  TickResult r;
  const Eigen::Vector3d p_silent = session.wrist_pose().translation();
  for (; k < 2 + 11; ++k) r = session.Step({}, k * kTick);  // 11 ticks = 0.183 s of silence
  EXPECT_FALSE(r.flags & kHoldingStill);
  EXPECT_GT((session.wrist_pose().translation() - p_silent).norm(), 0.01);  // still moving
  k += 2;
  r = session.Step({}, k++ * kTick);  // 13 ticks = 0.217 s
  EXPECT_TRUE(r.flags & kHoldingStill);
  const Eigen::Vector3d p_held = session.wrist_pose().translation();
  const Vector7d q_held = session.arm();
  for (int j = 0; j < 60; ++j) r = session.Step({}, k++ * kTick);
  EXPECT_TRUE(r.flags & kHoldingStill);
  EXPECT_LT((session.wrist_pose().translation() - p_held).norm(), 1e-3);
  EXPECT_LT((session.arm() - q_held).cwiseAbs().maxCoeff(), 2e-3);
  EXPECT_GT((session.wrist_pose().translation() - far.translation()).norm(), 0.05);
  // a new command takes over again.
  const Datagram d = Wrap(EncodeCommand(
      JointCommand(seq++, far, TeleopSession::RestHand(ShippedSimulationModel().robot()))));
  r = session.Step({&d, 1}, k++ * kTick);
  EXPECT_FALSE(r.flags & kHoldingStill);
}

// a huge jump of the target: every joint moves at most at its velocity cap.
TEST(TeleopSession, CapsJointVelocitiesWhateverTheOperatorSends) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  const Eigen::Isometry3d far = RestWrist(Eigen::Vector3d(-0.2, 0.2, 0.2));
  HandVector closed = Robot().hand.upper();
  const Vector7d arm_cap = Robot().arm.max_velocity() * kTick;
  const HandVector hand_cap = Robot().hand.max_velocity() * kTick;
  Vector7d q_cmd = session.arm_command();
  Vector7d q = session.arm();
  HandVector f_cmd = session.hand_command();
  double largest = 0.0;
  for (int k = 0; k < 60; ++k) {
    const Datagram d = Wrap(EncodeCommand(JointCommand(k, far, closed)));
    session.Step({&d, 1}, k * kTick);
    const Vector7d dq_cmd = (session.arm_command() - q_cmd).cwiseAbs();
    const Vector7d dq = (session.arm() - q).cwiseAbs();
    const HandVector df = (session.hand_command() - f_cmd).cwiseAbs();
    EXPECT_TRUE((dq_cmd.array() <= arm_cap.array() * (1 + 1e-9)).all()) << "tick " << k;
    EXPECT_TRUE((dq.array() <= arm_cap.array() * (1 + 1e-6) + 1e-9).all()) << "tick " << k;
    EXPECT_TRUE((df.array() <= hand_cap.array() * (1 + 1e-9)).all()) << "tick " << k;
    largest = std::max(largest, (dq.array() / arm_cap.array()).maxCoeff());
    q_cmd = session.arm_command();
    q = session.arm();
    f_cmd = session.hand_command();
  }
  EXPECT_GT(largest, 0.99);  // the cap was reached, not just respected
}

// glove mode: the 14 sensor values go through the glove map; the hand follows at its caps.
TEST(TeleopSession, GloveValuesDriveTheHandThroughTheGloveMap) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  Eigen::Matrix<double, 14, 1> g;
  for (int i = 0; i < 14; ++i) g[i] = (i % 3) / 2.0;
  const HandVector expected = GloveToJoints(GloveMap::Default(Robot().hand), Robot().hand, g);
  for (int k = 0; k < 120; ++k) {
    OperatorCommand c = JointCommand(k, RestWrist(), HandVector::Zero());
    c.hand_mode = HandMode::kGlove;
    c.fingers.head<14>() = g;
    const Datagram d = Wrap(EncodeCommand(c));
    session.Step({&d, 1}, k * kTick);
  }
  EXPECT_EQ(session.counters().commands_applied, 120u);
  EXPECT_LT((session.hand_command() - expected).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(TeleopSession, AnUnreachableTargetHoldsTheArm) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  Eigen::Isometry3d beyond = RestWrist();
  beyond.translation() = Eigen::Vector3d(3.0, 0.0, 0.5);  // far out of the arm's reach
  TickResult r;
  const Vector7d q0 = session.arm();
  for (int k = 0; k < 20; ++k) {
    const Datagram d = Wrap(EncodeCommand(
        JointCommand(k, beyond, TeleopSession::RestHand(ShippedSimulationModel().robot()))));
    r = session.Step({&d, 1}, k * kTick);
  }
  EXPECT_TRUE(r.flags & kOutOfReach);
  EXPECT_LT((session.arm() - q0).cwiseAbs().maxCoeff(), 1e-6);
}

// a trial with the grasp and end buttons is judged after the hold and written; the file passes
// the log reader and the summary lists it.
TEST(TeleopSession, RecordsATrialThatPassesTheLogReader) {
  TeleopOptions options = SixtyDegrees();
  options.record_dir = TempDir("record");
  options.end_hold_s = 0.5;
  options.operator_name = "unit test";
  TeleopSession session(ShippedSimulationModel(), options);
  const Eigen::Isometry3d start = RestWrist();
  const Eigen::Isometry3d lower = RestWrist(Eigen::Vector3d(0, 0, -0.05));
  std::optional<TrialRecord> ended;
  int k = 0;
  for (; k < 60 && !ended; ++k) {
    const double a = std::min(1.0, k / 40.0);
    Eigen::Isometry3d X = start;
    X.translation() = (1 - a) * start.translation() + a * lower.translation();
    const uint8_t buttons = k == 30 ? kGraspButton : k == 45 ? kEndTrialButton : 0;
    const Datagram d = Wrap(EncodeCommand(
        JointCommand(k, X, TeleopSession::RestHand(ShippedSimulationModel().robot()), buttons)));
    const TickResult r = session.Step({&d, 1}, k * kTick);
    if (k < 45) {
      EXPECT_TRUE(r.flags & kRecording) << k;
    } else if (k == 45) {
      EXPECT_TRUE(r.flags & kJudging);
    }
    ended = r.trial;
  }
  for (; k < 200 && !ended; ++k) ended = session.Step({}, k * kTick).trial;
  ASSERT_TRUE(ended);
  EXPECT_EQ(ended->outcome, TrialOutcome::kNotLifted);
  EXPECT_EQ(OutcomeName(*ended), "not_lifted");
  // the judgement of the offline trials, with its wording.
  EXPECT_NE(ended->reason.find("object not lifted: its centre rose at most"), std::string::npos)
      << ended->reason;
  EXPECT_FALSE(ended->success);
  EXPECT_TRUE(ended->has_grasp);
  ASSERT_FALSE(ended->file.empty()) << ended->not_written;
  // 45 ticks of commands, then 0.5 s of hold from the end press on.
  EXPECT_EQ(ended->samples, 45u + 30u);
  const DemoLog log = ReadDemoLog(ended->file);
  EXPECT_EQ(log.samples.size(), ended->samples);
  EXPECT_EQ(log.metadata.theta_deg, 60.0);
  EXPECT_EQ(log.metadata.operator_name.value_or(""), "unit test");
  ASSERT_TRUE(FindEvent(log, DemoEvent::kGrasp));
  EXPECT_EQ(*FindEvent(log, DemoEvent::kGrasp), 30u);
  EXPECT_EQ(log.samples.back().event, DemoEvent::kEnd);
  const SegmentedTrial segmented = Segment(log, SegmentationOptions{});
  EXPECT_FALSE(segmented.success);
  // the grasp sample's wrist is where the robot was at that tick.
  EXPECT_LT((log.samples[30].p_WH - lower.translation()).norm(), 0.03);

  const nlohmann::json summary = nlohmann::json::parse(session.SummaryJson("test", 1.0));
  EXPECT_EQ(summary["format"], "graspsynth-teleop-session/1");
  ASSERT_EQ(summary["trials"].size(), 1u);
  EXPECT_EQ(summary["trials"][0]["outcome"], "not_lifted");
  EXPECT_EQ(summary["trials"][0]["file"], ended->file.string());
  EXPECT_EQ(summary["packets"]["accepted"], 60);
  EXPECT_EQ(summary["packets"]["ignored_while_judging"], 60 - 46);
  EXPECT_EQ(summary["packets"]["dropped"]["bad_checksum"], 0);
  std::filesystem::remove_all(options.record_dir);
}

// the operator drives the hand down into the table beside the object: the arm-table contact
// decides the trial when it is judged, with the offline trials' outcome and wording.
TEST(TeleopSession, DrivingTheHandIntoTheTableIsACollision) {
  TeleopOptions options = SixtyDegrees();
  options.end_hold_s = 0.1;
  TeleopSession session(ShippedSimulationModel(), options);
  const Eigen::Isometry3d start = RestWrist();
  const Eigen::Isometry3d below = RestWrist(Eigen::Vector3d(-0.10, -0.10, -0.40));
  std::optional<TrialRecord> ended;
  int k = 0;
  for (; k < 200 && !ended; ++k) {
    const double a = std::min(1.0, k / 120.0);
    Eigen::Isometry3d X = start;
    X.translation() = (1 - a) * start.translation() + a * below.translation();
    const uint8_t buttons = k == 150 ? kEndTrialButton : 0;
    const Datagram d = Wrap(EncodeCommand(
        JointCommand(k, X, TeleopSession::RestHand(ShippedSimulationModel().robot()), buttons)));
    ended = session.Step({&d, 1}, k * kTick).trial;
  }
  for (; k < 300 && !ended; ++k) ended = session.Step({}, k * kTick).trial;
  ASSERT_TRUE(ended);
  EXPECT_EQ(ended->outcome, TrialOutcome::kCollision) << ended->reason;
  EXPECT_EQ(OutcomeName(*ended), "collision");
  EXPECT_NE(ended->reason.find(" hit the table at t = "), std::string::npos) << ended->reason;
}

TEST(TeleopSession, ATrialWithoutAGraspIsJudgedButNotWritten) {
  TeleopOptions options = SixtyDegrees();
  options.record_dir = TempDir("nograsp");
  options.end_hold_s = 0.1;
  TeleopSession session(ShippedSimulationModel(), options);
  std::optional<TrialRecord> ended;
  for (int k = 0; k < 40 && !ended; ++k) {
    const uint8_t buttons = k == 10 ? kEndTrialButton : 0;
    const Datagram d = Wrap(EncodeCommand(JointCommand(
        k, RestWrist(), TeleopSession::RestHand(ShippedSimulationModel().robot()), buttons)));
    ended = session.Step({&d, 1}, k * kTick).trial;
  }
  ASSERT_TRUE(ended);
  EXPECT_TRUE(ended->file.empty());
  EXPECT_NE(ended->not_written.find("grasp"), std::string::npos);
  EXPECT_TRUE(std::filesystem::is_empty(options.record_dir));
  std::filesystem::remove_all(options.record_dir);
}

TEST(TeleopSession, NextOrientationAbandonsTheTrialAndResetsTheWorld) {
  TeleopOptions options;
  options.orientations_deg = {60.0, 80.0};
  TeleopSession session(ShippedSimulationModel(), options);
  const Eigen::Isometry3d X = RestWrist(Eigen::Vector3d(0, 0, -0.03));
  for (int k = 0; k < 10; ++k) {
    const Datagram d = Wrap(EncodeCommand(
        JointCommand(k, X, TeleopSession::RestHand(ShippedSimulationModel().robot()))));
    session.Step({&d, 1}, k * kTick);
  }
  const Datagram next = Wrap(EncodeCommand(JointCommand(
      10, X, TeleopSession::RestHand(ShippedSimulationModel().robot()), kNextOrientationButton)));
  const TickResult r = session.Step({&next, 1}, 10 * kTick);
  EXPECT_EQ(session.theta_deg(), 80.0);
  ASSERT_TRUE(r.trial);
  EXPECT_FALSE(r.trial->outcome.has_value());
  EXPECT_EQ(OutcomeName(*r.trial), "abandoned");
  const Vector7d rest80 = TeleopSession::RestArm(Robot(), ShippedSimulationModel().scene(), 80.0);
  EXPECT_LT((session.arm() - rest80).cwiseAbs().maxCoeff(), 1e-6);
  const double theta = 80.0 * M_PI / 180.0;
  EXPECT_LT((session.object_pose().translation() -
             ShippedSimulationModel().scene().ObjectPose(theta).translation())
                .norm(),
            2e-3);
}

TEST(TeleopSession, AnEndOfSessionPacketFinishesTheSession) {
  TeleopSession session(ShippedSimulationModel(), SixtyDegrees());
  const Datagram c = Wrap(EncodeCommand(
      JointCommand(0, RestWrist(), TeleopSession::RestHand(ShippedSimulationModel().robot()))));
  EXPECT_FALSE(session.Step({&c, 1}, 0.0).finished);
  const Datagram end = Wrap(EncodeEndOfSession(1, 0.1));
  const TickResult r = session.Step({&end, 1}, kTick);
  EXPECT_TRUE(r.finished);
  EXPECT_TRUE(session.finished());
  ASSERT_TRUE(r.trial);  // the open trial had no end: abandoned
  EXPECT_FALSE(r.trial->outcome.has_value());
  EXPECT_EQ(OutcomeName(*r.trial), "abandoned");
  const nlohmann::json summary = nlohmann::json::parse(session.SummaryJson("test", 1.0));
  EXPECT_EQ(summary["trials"][0]["outcome"], "abandoned");
}

// With a key, only authenticated commands drive the robot: plain ones, forged ones and
// replays of recorded authenticated ones are counted by reason and never applied; the states
// go back authenticated.
TEST(TeleopSession, WithAKeyOnlyFreshAuthenticatedCommandsDriveTheRobot) {
  TeleopOptions options = SixtyDegrees();
  options.key = PacketKey(std::vector<uint8_t>(32, 0x42));
  const PacketKey& key = *options.key;
  const PacketKey stranger(std::vector<uint8_t>(32, 0x43));
  TeleopSession session(ShippedSimulationModel(), options);
  const HandVector f = TeleopSession::RestHand(ShippedSimulationModel().robot());
  const Eigen::Isometry3d target = RestWrist(Eigen::Vector3d(0.05, 0.0, -0.04));
  const Eigen::Isometry3d wild = RestWrist(Eigen::Vector3d(0.0, 0.0, -0.3));
  std::vector<std::vector<uint8_t>> recorded;
  const int ticks = 60;
  TickResult r;
  for (int k = 0; k < ticks; ++k) {
    const uint32_t seq = 1000 + static_cast<uint32_t>(k);
    std::vector<Datagram> in;
    in.push_back(Wrap(EncodeCommand(JointCommand(seq + 500, wild, f))));  // plain
    in.push_back(Wrap(EncodeCommand(JointCommand(seq + 500, wild, f), &stranger)));
    recorded.push_back(EncodeCommand(JointCommand(seq, target, f), &key));
    in.push_back(Wrap(recorded.back()));
    if (k >= 2) in.push_back(Wrap(recorded[k - 2]));  // a replay of an older packet
    in.push_back(Wrap(recorded.back()));              // and of this one
    r = session.Step(in, k * kTick);
  }
  const PacketCounters& c = session.counters();
  const auto dropped = [&](DropReason reason) { return c.dropped[static_cast<int>(reason)]; };
  EXPECT_EQ(c.commands_applied, static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kUnauthenticated), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kBadTag), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kDuplicate), static_cast<uint64_t>(ticks));
  EXPECT_EQ(dropped(DropReason::kOutOfOrder), static_cast<uint64_t>(ticks - 2));
  EXPECT_EQ(c.received, c.accepted + c.dropped_total());
  EXPECT_LT((session.wrist_pose().translation() - target.translation()).norm(), 2e-3);
  ASSERT_FALSE(r.state_packet.empty());
  EXPECT_TRUE(Decode(r.state_packet, &key).packet);
  EXPECT_EQ(Decode(r.state_packet).reason, DropReason::kBadTag);
  const nlohmann::json summary = nlohmann::json::parse(session.SummaryJson("test", 1.0));
  EXPECT_TRUE(summary["authenticated"].get<bool>());
  EXPECT_EQ(summary["packets"]["dropped"]["unauthenticated"], ticks);
  EXPECT_EQ(summary["packets"]["dropped"]["bad_tag"], ticks);
}

}  // namespace
}  // namespace graspsynth::teleop
