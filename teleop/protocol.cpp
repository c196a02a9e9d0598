#include "teleop/protocol.hpp"

#include <bit>
#include <cmath>
#include <cstring>

namespace graspsynth::teleop {
namespace {

static_assert(std::endian::native == std::endian::little,
              "the wire format is little-endian; add byte swapping for this platform");

// limits of the values a packet may carry.
constexpr double kMaxPosition = 10.0;     // m
constexpr double kMaxJoint = 2.0 * M_PI;  // rad
constexpr double kQuaternionTol = 1e-3;
constexpr uint8_t kKnownButtons = kGraspButton | kEndTrialButton | kNextOrientationButton;

class Writer {
 public:
  explicit Writer(size_t reserve) { bytes_.reserve(reserve); }
  template <typename T>
  void Put(const T& value) {
    const auto* p = reinterpret_cast<const uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void PutVector(const double* values, int count) {
    for (int i = 0; i < count; ++i) Put(values[i]);
  }
  std::vector<uint8_t> Finish(const PacketKey* key) {
    Put(Crc32(bytes_));
    if (key != nullptr) {
      const std::array<uint8_t, kTagBytes> tag = key->Tag(bytes_);
      bytes_.insert(bytes_.end(), tag.begin(), tag.end());
    }
    return std::move(bytes_);
  }

 private:
  std::vector<uint8_t> bytes_;
};

class Reader {
 public:
  Reader(std::span<const uint8_t> bytes, size_t offset) : bytes_(bytes), pos_(offset) {}
  template <typename T>
  T Get() {
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  void GetVector(double* values, int count) {
    for (int i = 0; i < count; ++i) values[i] = Get<double>();
  }

 private:
  std::span<const uint8_t> bytes_;
  size_t pos_;
};

void PutHeader(Writer& w, PacketKind kind, uint32_t sequence, uint32_t payload, double time,
               const PacketKey* key) {
  for (uint8_t b : kMagic) w.Put(b);
  w.Put(key != nullptr ? kAuthenticatedVersion : kVersion);
  w.Put(static_cast<uint16_t>(kind));
  w.Put(sequence);
  w.Put(payload);
  w.Put(time);
}

bool Finite(const double* values, int count) {
  for (int i = 0; i < count; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

DecodeResult Drop(DropReason reason) {
  DecodeResult r;
  r.reason = reason;
  return r;
}

bool CommandValuesOk(const OperatorCommand& c) {
  if (!c.p_TW.allFinite() || !c.q_TW.coeffs().allFinite() || !c.fingers.allFinite()) return false;
  if (c.p_TW.cwiseAbs().maxCoeff() > kMaxPosition) return false;
  if (std::abs(c.q_TW.norm() - 1.0) > kQuaternionTol) return false;
  if ((c.buttons & ~kKnownButtons) != 0) return false;
  if (c.hand_mode == HandMode::kGlove) {
    const auto glove = c.fingers.head<kGloveSensors>();
    return (glove.array() >= 0.0).all() && (glove.array() <= 1.0).all() &&
           c.fingers.tail<kHandDof - kGloveSensors>().isZero(0.0);
  }
  return c.fingers.cwiseAbs().maxCoeff() <= kMaxJoint;
}

}  // namespace

std::string_view ToString(DropReason reason) {
  switch (reason) {
    case DropReason::kShort:
      return "short";
    case DropReason::kBadMagic:
      return "bad_magic";
    case DropReason::kBadVersion:
      return "bad_version";
    case DropReason::kBadLength:
      return "bad_length";
    case DropReason::kBadChecksum:
      return "bad_checksum";
    case DropReason::kUnknownKind:
      return "unknown_kind";
    case DropReason::kBadValue:
      return "bad_value";
    case DropReason::kDuplicate:
      return "duplicate";
    case DropReason::kOutOfOrder:
      return "out_of_order";
    case DropReason::kUnauthenticated:
      return "unauthenticated";
    case DropReason::kBadTag:
      return "bad_tag";
  }
  return "unknown";
}

uint32_t Crc32(std::span<const uint8_t> bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  for (uint8_t b : bytes) crc = table[(crc ^ b) & 0xFFu] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

std::vector<uint8_t> EncodeCommand(const OperatorCommand& c, const PacketKey* key) {
  Writer w(kHeaderBytes + kCommandPayloadBytes + kCrcBytes + kTagBytes);
  PutHeader(w, PacketKind::kCommand, c.sequence, kCommandPayloadBytes, c.sender_time, key);
  w.PutVector(c.p_TW.data(), 3);
  const double q[4] = {c.q_TW.w(), c.q_TW.x(), c.q_TW.y(), c.q_TW.z()};
  w.PutVector(q, 4);
  w.Put(static_cast<uint8_t>(c.hand_mode));
  w.Put(c.buttons);
  w.Put(static_cast<uint16_t>(0));
  w.PutVector(c.fingers.data(), kHandDof);
  return w.Finish(key);
}

std::vector<uint8_t> EncodeState(const RobotStateMessage& s, const PacketKey* key) {
  Writer w(kHeaderBytes + kStatePayloadBytes + kCrcBytes + kTagBytes);
  PutHeader(w, PacketKind::kState, s.sequence, kStatePayloadBytes, s.sender_time, key);
  w.PutVector(s.arm.data(), kArmDof);
  w.PutVector(s.hand.data(), kHandDof);
  w.PutVector(s.p_WO.data(), 3);
  const double q[4] = {s.q_WO.w(), s.q_WO.x(), s.q_WO.y(), s.q_WO.z()};
  w.PutVector(q, 4);
  w.Put(s.theta_deg);
  w.Put(s.trial);
  w.Put(s.flags);
  return w.Finish(key);
}

std::vector<uint8_t> EncodeEndOfSession(uint32_t sequence, double sender_time,
                                        const PacketKey* key) {
  Writer w(kHeaderBytes + kCrcBytes + kTagBytes);
  PutHeader(w, PacketKind::kEndOfSession, sequence, 0, sender_time, key);
  return w.Finish(key);
}

DecodeResult Decode(std::span<const uint8_t> datagram, const PacketKey* key) {
  if (datagram.size() < kHeaderBytes + kCrcBytes) return Drop(DropReason::kShort);
  if (!std::equal(kMagic.begin(), kMagic.end(), datagram.begin())) {
    return Drop(DropReason::kBadMagic);
  }
  Reader header(datagram, 4);
  const auto version = header.Get<uint16_t>();
  if (version != kVersion && version != kAuthenticatedVersion) {
    return Drop(DropReason::kBadVersion);
  }
  const size_t tag_bytes = version == kAuthenticatedVersion ? kTagBytes : 0;
  if (datagram.size() < kHeaderBytes + kCrcBytes + tag_bytes) return Drop(DropReason::kShort);
  // d: the packet up to its checksum (the tag follows in version 2).
  const std::span<const uint8_t> d = datagram.first(datagram.size() - tag_bytes);
  const auto kind = header.Get<uint16_t>();
  const auto sequence = header.Get<uint32_t>();
  const auto payload = header.Get<uint32_t>();
  const auto time = header.Get<double>();
  if (static_cast<size_t>(payload) != d.size() - kHeaderBytes - kCrcBytes) {
    return Drop(DropReason::kBadLength);
  }
  uint32_t crc;
  std::memcpy(&crc, d.data() + d.size() - kCrcBytes, kCrcBytes);
  if (crc != Crc32(d.first(d.size() - kCrcBytes))) return Drop(DropReason::kBadChecksum);
  if (key != nullptr && tag_bytes == 0) return Drop(DropReason::kUnauthenticated);
  if (tag_bytes != 0 && (key == nullptr || !key->Verifies(d, datagram.last(kTagBytes)))) {
    return Drop(DropReason::kBadTag);
  }

  DecodedPacket p;
  p.sequence = sequence;
  p.sender_time = time;
  if (!std::isfinite(time)) return Drop(DropReason::kBadValue);
  Reader r(d, kHeaderBytes);
  switch (kind) {
    case static_cast<uint16_t>(PacketKind::kCommand): {
      if (payload != kCommandPayloadBytes) return Drop(DropReason::kBadLength);
      p.kind = PacketKind::kCommand;
      OperatorCommand& c = p.command;
      c.sequence = sequence;
      c.sender_time = time;
      r.GetVector(c.p_TW.data(), 3);
      double q[4];
      r.GetVector(q, 4);
      c.q_TW = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      const auto mode = r.Get<uint8_t>();
      if (mode > 1) return Drop(DropReason::kBadValue);
      c.hand_mode = static_cast<HandMode>(mode);
      c.buttons = r.Get<uint8_t>();
      if (r.Get<uint16_t>() != 0) return Drop(DropReason::kBadValue);
      r.GetVector(c.fingers.data(), kHandDof);
      if (!CommandValuesOk(c)) return Drop(DropReason::kBadValue);
      break;
    }
    case static_cast<uint16_t>(PacketKind::kState): {
      if (payload != kStatePayloadBytes) return Drop(DropReason::kBadLength);
      p.kind = PacketKind::kState;
      RobotStateMessage& s = p.state;
      s.sequence = sequence;
      s.sender_time = time;
      r.GetVector(s.arm.data(), kArmDof);
      r.GetVector(s.hand.data(), kHandDof);
      r.GetVector(s.p_WO.data(), 3);
      double q[4];
      r.GetVector(q, 4);
      s.q_WO = Eigen::Quaterniond(q[0], q[1], q[2], q[3]);
      s.theta_deg = r.Get<double>();
      s.trial = r.Get<uint32_t>();
      s.flags = r.Get<uint32_t>();
      if (!Finite(s.arm.data(), kArmDof) || !Finite(s.hand.data(), kHandDof) ||
          !s.p_WO.allFinite() || !s.q_WO.coeffs().allFinite() || !std::isfinite(s.theta_deg)) {
        return Drop(DropReason::kBadValue);
      }
      break;
    }
    case static_cast<uint16_t>(PacketKind::kEndOfSession):
      if (payload != 0) return Drop(DropReason::kBadLength);
      p.kind = PacketKind::kEndOfSession;
      break;
    default:
      return Drop(DropReason::kUnknownKind);
  }
  DecodeResult result;
  result.packet = p;
  return result;
}

std::optional<DropReason> SequenceFilter::Check(uint32_t sequence) {
  if (seen_) {
    if (sequence == last_) return DropReason::kDuplicate;
    // unsigned difference: a forward step (also across the 2^32 wrap) is below 2^31.
    if (static_cast<uint32_t>(sequence - last_) >= 0x80000000u) return DropReason::kOutOfOrder;
  }
  seen_ = true;
  last_ = sequence;
  return std::nullopt;
}

}  // namespace graspsynth::teleop
