#pragma once

/// @file
/// The teleoperation wire format: binary UDP datagrams, little-endian, each
///
///   offset  size  field
///        0     4  magic "GSTP" (bytes 0x47 0x53 0x54 0x50)
///        4     2  version: 1, or 2 for an authenticated packet
///        6     2  kind: 1 operator command, 2 robot state, 3 end of session
///        8     4  sequence number (uint32), increasing per sender
///       12     4  payload length in bytes (uint32)
///       16     8  sender time, s (IEEE-754 double)
///       24     n  payload (layout per kind, below)
///     24+n     4  CRC-32 (IEEE 802.3, as zlib's crc32) of bytes 0 .. 24+n-1
///     28+n    32  version 2 only: HMAC-SHA256 of bytes 0 .. 28+n-1 with the shared key
///                 (teleop/packet_key.hpp)
///
/// A receiver with a key takes only version 2 packets whose tag verifies; one without a key
/// takes only version 1 packets. The sequence number is under the tag, so a replayed packet is
/// a duplicate or out of order for the receiver's SequenceFilter.
///
/// Operator command payload (188 bytes): wrist position x, y, z (3 doubles, m, tracker frame),
/// wrist quaternion w, x, y, z (4 doubles), hand mode (uint8: 0 glove, 1 joints), buttons
/// (uint8 bitmask: 1 grasp, 2 end of trial, 4 next orientation), 2 reserved bytes (0), then 16
/// doubles: in glove mode the 14 glove sensor values in [0, 1] (5DT order, reference/robot.md
/// 3.1) followed by two zeros, in joint mode the finger joints f0..f15 in radians.
/// Robot state payload (256 bytes): arm joints (7 doubles, rad), finger joints f0..f15
/// (16 doubles), object position (3 doubles, m, world) and quaternion w, x, y, z (4 doubles),
/// object orientation theta (1 double, deg), trial index (uint32), flags (uint32, StateFlag:
/// 1 holding still after a silence, 2 recording, 4 last trial succeeded, 8 the wrist target is
/// out of reach and the arm holds, 16 judging a trial (the hold after the end-of-trial button)).
/// End-of-session payload: empty.

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "kinematics/types.hpp"
#include "teleop/packet_key.hpp"

namespace graspsynth::teleop {

inline constexpr std::array<uint8_t, 4> kMagic = {'G', 'S', 'T', 'P'};
inline constexpr uint16_t kVersion = 1;
inline constexpr uint16_t kAuthenticatedVersion = 2;
inline constexpr size_t kHeaderBytes = 24;
inline constexpr size_t kCrcBytes = 4;
inline constexpr size_t kCommandPayloadBytes = 188;
inline constexpr size_t kStatePayloadBytes = 256;
inline constexpr int kGloveSensors = 14;

enum class PacketKind : uint16_t { kCommand = 1, kState = 2, kEndOfSession = 3 };

/// Button bits of an operator command.
enum Button : uint8_t { kGraspButton = 1, kEndTrialButton = 2, kNextOrientationButton = 4 };

/// Flag bits of a robot state.
enum StateFlag : uint32_t {
  kHoldingStill = 1,        ///< no operator command for longer than the timeout
  kRecording = 2,           ///< a trial is being recorded
  kLastTrialSucceeded = 4,  ///< the last judged trial was a success
  kOutOfReach = 8,          ///< the last wrist target had no IK solution: the arm holds
  kJudging = 16,            ///< the hold after the end-of-trial button, before the judgement
};

/// How the finger values of a command are to be read.
enum class HandMode : uint8_t { kGlove = 0, kJoints = 1 };

/// An operator command: where the operator's wrist is and what the hand does.
struct OperatorCommand {
  uint32_t sequence = 0;
  double sender_time = 0.0;                                  ///< s
  Eigen::Vector3d p_TW = Eigen::Vector3d::Zero();            ///< wrist position, tracker frame, m
  Eigen::Quaterniond q_TW = Eigen::Quaterniond::Identity();  ///< wrist orientation, tracker frame
  HandMode hand_mode = HandMode::kJoints;
  uint8_t buttons = 0;
  HandVector fingers = HandVector::Zero();  ///< glove values (first 14) or joints f0..f15, rad
};

/// The robot and object state streamed back to the operator.
struct RobotStateMessage {
  uint32_t sequence = 0;
  double sender_time = 0.0;
  Vector7d arm = Vector7d::Zero();
  HandVector hand = HandVector::Zero();
  Eigen::Vector3d p_WO = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q_WO = Eigen::Quaterniond::Identity();
  double theta_deg = 0.0;
  uint32_t trial = 0;
  uint32_t flags = 0;
};

/// Why a datagram was dropped. Each reason has its own counter in a session summary.
enum class DropReason {
  kShort,            ///< fewer bytes than a header and a checksum
  kBadMagic,         ///< not a graspsynth teleoperation packet
  kBadVersion,       ///< another version of the format
  kBadLength,        ///< the payload length disagrees with the datagram or the kind
  kBadChecksum,      ///< CRC-32 mismatch
  kUnknownKind,      ///< a kind this receiver does not take
  kBadValue,         ///< NaN, infinity, a non-unit quaternion, a value out of range
  kDuplicate,        ///< the sequence number of the last applied packet
  kOutOfOrder,       ///< older than the last applied packet
  kUnauthenticated,  ///< a version 1 packet where the receiver requires a key
  kBadTag,  ///< an authenticated packet whose tag does not verify (or the receiver has no key)
};
inline constexpr int kDropReasonCount = 11;

/// Short name of a drop reason for reports, e.g. "bad_checksum".
std::string_view ToString(DropReason reason);

/// CRC-32 (IEEE 802.3 polynomial, reflected, as zlib's crc32) of `bytes`.
uint32_t Crc32(std::span<const uint8_t> bytes);

/// Encodes a command, a state or an end-of-session packet: version 1 without a key, version 2
/// with its tag with one.
std::vector<uint8_t> EncodeCommand(const OperatorCommand& command, const PacketKey* key = nullptr);
std::vector<uint8_t> EncodeState(const RobotStateMessage& state, const PacketKey* key = nullptr);
std::vector<uint8_t> EncodeEndOfSession(uint32_t sequence, double sender_time,
                                        const PacketKey* key = nullptr);

/// A decoded datagram: its kind and, for commands and states, the content.
struct DecodedPacket {
  PacketKind kind = PacketKind::kCommand;
  uint32_t sequence = 0;
  double sender_time = 0.0;
  OperatorCommand command;  ///< valid when kind == kCommand
  RobotStateMessage state;  ///< valid when kind == kState
};

/// Result of decoding: the packet, or why it must be dropped.
struct DecodeResult {
  std::optional<DecodedPacket> packet;
  DropReason reason = DropReason::kShort;  ///< meaningful when packet is empty
};

/// Decodes and checks one datagram: framing (size, magic, version, length, checksum), the
/// authentication (with `key`: a version 2 packet whose tag verifies; without: version 1), and
/// values (finite numbers, unit wrist quaternion within 1e-3, position within 10 m, glove
/// values in [0, 1], joint values within +-2 pi, buttons within the defined bits). Never
/// throws, whatever the bytes. Sequence checks are the receiver's (SequenceFilter).
DecodeResult Decode(std::span<const uint8_t> datagram, const PacketKey* key = nullptr);

/// Accepts each sequence number once and in increasing order (wrap-around of the 32-bit counter
/// is taken as increasing when the jump is below 2^31).
class SequenceFilter {
 public:
  /// std::nullopt when `sequence` may be applied (and remembers it), else why not.
  std::optional<DropReason> Check(uint32_t sequence);

 private:
  bool seen_ = false;
  uint32_t last_ = 0;
};

}  // namespace graspsynth::teleop
