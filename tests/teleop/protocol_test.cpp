#include "teleop/protocol.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::teleop {
namespace {

OperatorCommand SampleCommand() {
  OperatorCommand c;
  c.sequence = 42;
  c.sender_time = 12.5;
  c.p_TW = Eigen::Vector3d(0.1, -0.2, 0.3);
  c.q_TW = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()));
  c.hand_mode = HandMode::kJoints;
  c.buttons = kGraspButton;
  c.fingers = HandVector::LinSpaced(0.0, 1.5);
  return c;
}

TEST(Crc32, MatchesTheStandardCheckValue) {
  const std::string text = "123456789";
  EXPECT_EQ(Crc32({reinterpret_cast<const uint8_t*>(text.data()), text.size()}), 0xCBF43926u);
}

TEST(Protocol, CommandRoundTrip) {
  const OperatorCommand c = SampleCommand();
  const std::vector<uint8_t> bytes = EncodeCommand(c);
  EXPECT_EQ(bytes.size(), kHeaderBytes + kCommandPayloadBytes + kCrcBytes);
  EXPECT_EQ(bytes[0], 'G');
  const DecodeResult r = Decode(bytes);
  ASSERT_TRUE(r.packet);
  EXPECT_EQ(r.packet->kind, PacketKind::kCommand);
  const OperatorCommand& d = r.packet->command;
  EXPECT_EQ(d.sequence, 42u);
  EXPECT_EQ(d.sender_time, 12.5);
  EXPECT_TRUE(testing::MatricesNear(d.p_TW, c.p_TW, 0.0));
  EXPECT_TRUE(testing::MatricesNear(d.q_TW.coeffs(), c.q_TW.coeffs(), 0.0));
  EXPECT_EQ(d.buttons, kGraspButton);
  EXPECT_TRUE(testing::MatricesNear(d.fingers, c.fingers, 0.0));
}

TEST(Protocol, StateAndEndOfSessionRoundTrip) {
  RobotStateMessage s;
  s.sequence = 7;
  s.arm = Vector7d::LinSpaced(-1.0, 1.0);
  s.hand = HandVector::Constant(0.25);
  s.p_WO = Eigen::Vector3d(-0.25, 0.85, 0.025);
  s.theta_deg = 60.0;
  s.trial = 3;
  s.flags = 2;
  const DecodeResult r = Decode(EncodeState(s));
  ASSERT_TRUE(r.packet);
  EXPECT_EQ(r.packet->kind, PacketKind::kState);
  EXPECT_TRUE(testing::MatricesNear(r.packet->state.arm, s.arm, 0.0));
  EXPECT_EQ(r.packet->state.trial, 3u);
  EXPECT_EQ(r.packet->state.theta_deg, 60.0);
  const DecodeResult e = Decode(EncodeEndOfSession(9, 1.0));
  ASSERT_TRUE(e.packet);
  EXPECT_EQ(e.packet->kind, PacketKind::kEndOfSession);
  EXPECT_EQ(e.packet->sequence, 9u);
}

// re-seals a modified packet with a valid checksum, so that only the change is tested.
std::vector<uint8_t> Reseal(std::vector<uint8_t> bytes) {
  bytes.resize(bytes.size() - kCrcBytes);
  const uint32_t crc = Crc32(bytes);
  const auto* p = reinterpret_cast<const uint8_t*>(&crc);
  bytes.insert(bytes.end(), p, p + 4);
  return bytes;
}

TEST(Protocol, StateFlagsAreDistinctBitsAndRoundTrip) {
  const uint32_t all = kHoldingStill | kRecording | kLastTrialSucceeded | kOutOfReach | kJudging;
  EXPECT_EQ(all, 31u);
  RobotStateMessage s;
  s.flags = kHoldingStill | kOutOfReach | kJudging;
  const DecodeResult r = Decode(EncodeState(s));
  ASSERT_TRUE(r.packet);
  EXPECT_EQ(r.packet->state.flags, 25u);
}

TEST(Protocol, EachDefectHasItsReason) {
  const std::vector<uint8_t> good = EncodeCommand(SampleCommand());
  EXPECT_EQ(Decode(std::span(good).first(20)).reason, DropReason::kShort);

  std::vector<uint8_t> b = good;
  b[0] = 'X';
  EXPECT_EQ(Decode(b).reason, DropReason::kBadMagic);

  b = good;
  b[4] = 3;  // 1 is plain, 2 authenticated
  EXPECT_EQ(Decode(Reseal(b)).reason, DropReason::kBadVersion);

  b = good;
  b.insert(b.end() - 4, 0);  // one payload byte more than the header says
  EXPECT_EQ(Decode(Reseal(b)).reason, DropReason::kBadLength);

  b = good;
  b[40] ^= 0x01;  // flipped bit, checksum not updated
  EXPECT_EQ(Decode(b).reason, DropReason::kBadChecksum);

  b = good;
  b[6] = 9;
  EXPECT_EQ(Decode(Reseal(b)).reason, DropReason::kUnknownKind);

  OperatorCommand c = SampleCommand();
  c.p_TW.x() = std::nan("");
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
  c = SampleCommand();
  c.q_TW.coeffs() *= 2.0;
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
  c = SampleCommand();
  c.hand_mode = HandMode::kGlove;
  c.fingers.setConstant(0.5);  // the two unused glove slots must be zero
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
  c.fingers.tail<2>().setZero();
  c.fingers[3] = 1.5;  // glove values are in [0, 1]
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
  c = SampleCommand();
  c.buttons = 0x80;
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
  c = SampleCommand();
  c.fingers[0] = 100.0;
  EXPECT_EQ(Decode(EncodeCommand(c)).reason, DropReason::kBadValue);
}

// RFC 4231's first test case of HMAC-SHA256: 20 bytes 0x0b, the text "Hi There".
TEST(PacketKey, MatchesTheStandardHmacSha256TestVector) {
  const PacketKey key(std::vector<uint8_t>(20, 0x0b));
  const std::string text = "Hi There";
  const std::array<uint8_t, kTagBytes> tag =
      key.Tag({reinterpret_cast<const uint8_t*>(text.data()), text.size()});
  const std::array<uint8_t, kTagBytes> expected = {0xb0, 0x34, 0x4c, 0x61, 0xd8, 0xdb, 0x38, 0x53,
                                                   0x5c, 0xa8, 0xaf, 0xce, 0xaf, 0x0b, 0xf1, 0x2b,
                                                   0x88, 0x1d, 0xc2, 0x00, 0xc9, 0x83, 0x3d, 0xa7,
                                                   0x26, 0xe9, 0x37, 0x6c, 0x2e, 0x32, 0xcf, 0xf7};
  EXPECT_EQ(tag, expected);
}

// re-seals a modified version 2 packet with a valid checksum and its old tag: what an attacker
// without the key can do.
std::vector<uint8_t> ResealKeepingTheTag(std::vector<uint8_t> bytes) {
  const std::vector<uint8_t> tag(bytes.end() - kTagBytes, bytes.end());
  bytes.resize(bytes.size() - kTagBytes);
  bytes = Reseal(std::move(bytes));
  bytes.insert(bytes.end(), tag.begin(), tag.end());
  return bytes;
}

TEST(Protocol, AuthenticatedPacketsRoundTripAndEverythingElseIsRefused) {
  const PacketKey key(std::vector<uint8_t>(20, 0x0b));
  const PacketKey other(std::vector<uint8_t>(20, 0x0c));
  const std::vector<uint8_t> good = EncodeCommand(SampleCommand(), &key);
  EXPECT_EQ(good.size(), kHeaderBytes + kCommandPayloadBytes + kCrcBytes + kTagBytes);
  EXPECT_EQ(good[4], kAuthenticatedVersion);
  const DecodeResult r = Decode(good, &key);
  ASSERT_TRUE(r.packet);
  EXPECT_EQ(r.packet->command.sequence, 42u);
  EXPECT_TRUE(testing::MatricesNear(r.packet->command.fingers, SampleCommand().fingers, 0.0));
  RobotStateMessage s;
  s.trial = 4;
  const DecodeResult state = Decode(EncodeState(s, &key), &key);
  ASSERT_TRUE(state.packet);
  EXPECT_EQ(state.packet->state.trial, 4u);
  EXPECT_TRUE(Decode(EncodeEndOfSession(3, 1.0, &key), &key).packet);

  // a plain packet where a key is required; another key; no key to check the tag with.
  EXPECT_EQ(Decode(EncodeCommand(SampleCommand()), &key).reason, DropReason::kUnauthenticated);
  EXPECT_EQ(Decode(good, &other).reason, DropReason::kBadTag);
  EXPECT_EQ(Decode(good).reason, DropReason::kBadTag);
  // any change, its checksum made right again: the sequence number, a finger, the tag itself.
  for (size_t at : {size_t{8}, size_t{100}, good.size() - 1}) {
    std::vector<uint8_t> forged = good;
    forged[at] ^= 0x01;
    if (at < good.size() - kTagBytes) forged = ResealKeepingTheTag(forged);
    EXPECT_EQ(Decode(forged, &key).reason, DropReason::kBadTag) << at;
  }
  // a plain packet relabelled as version 2, with a made-up tag.
  std::vector<uint8_t> relabelled = EncodeCommand(SampleCommand());
  relabelled[4] = kAuthenticatedVersion;
  relabelled = Reseal(relabelled);
  relabelled.insert(relabelled.end(), kTagBytes, 0);
  EXPECT_EQ(Decode(relabelled, &key).reason, DropReason::kBadTag);
  // the tag cut off.
  EXPECT_NE(Decode(std::span(good).first(good.size() - kTagBytes), &key).reason,
            DropReason::kBadTag);
  EXPECT_FALSE(Decode(std::span(good).first(good.size() - kTagBytes), &key).packet);
}

TEST(Protocol, RandomBytesNeverCrashAndNeverDecode) {
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<int> byte(0, 255);
  std::uniform_int_distribution<int> length(0, 400);
  const std::vector<uint8_t> good = EncodeCommand(SampleCommand());
  int decoded = 0;
  for (int k = 0; k < 20000; ++k) {
    std::vector<uint8_t> b;
    if (k % 2 == 0) {
      b.resize(static_cast<size_t>(length(rng)));
      for (auto& x : b) x = static_cast<uint8_t>(byte(rng));
    } else {
      b = good;  // a valid packet with a few random bytes changed
      for (int j = 0; j < 3; ++j) b[static_cast<size_t>(length(rng)) % b.size()] = byte(rng);
    }
    decoded += Decode(b).packet.has_value() && b != good;
  }
  EXPECT_EQ(decoded, 0);
  // the same with a key, on authenticated packets.
  const PacketKey key(std::vector<uint8_t>(16, 0x5a));
  const std::vector<uint8_t> signed_good = EncodeCommand(SampleCommand(), &key);
  for (int k = 0; k < 20000; ++k) {
    std::vector<uint8_t> b = signed_good;
    for (int j = 0; j < 3; ++j) b[static_cast<size_t>(length(rng)) % b.size()] = byte(rng);
    decoded += Decode(b, &key).packet.has_value() && b != signed_good;
  }
  EXPECT_EQ(decoded, 0);
}

TEST(SequenceFilter, DropsDuplicatesAndOlderPackets) {
  SequenceFilter f;
  EXPECT_FALSE(f.Check(10));
  EXPECT_EQ(f.Check(10), DropReason::kDuplicate);
  EXPECT_EQ(f.Check(9), DropReason::kOutOfOrder);
  EXPECT_FALSE(f.Check(12));
  EXPECT_EQ(f.Check(11), DropReason::kOutOfOrder);
  // the 32-bit counter wraps around forward.
  SequenceFilter w;
  EXPECT_FALSE(w.Check(0xFFFFFFFEu));
  EXPECT_FALSE(w.Check(1u));
  EXPECT_EQ(w.Check(0xFFFFFFFFu), DropReason::kOutOfOrder);
}

}  // namespace
}  // namespace graspsynth::teleop
