// Teleoperation datagrams (GSTP v1 and v2, teleop/protocol.hpp). Decode never throws; the
// first byte chooses whether the receiver has a key. A datagram that decodes must encode back
// to the same bytes.
#include <cstdlib>
#include <vector>

#include "fuzz/fuzz_support.hpp"
#include "teleop/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth::teleop;
  if (size == 0) return 0;
  static const PacketKey key(std::vector<uint8_t>(32, 0x24));
  const PacketKey* receiver = data[0] % 2 == 0 ? nullptr : &key;
  const std::span<const uint8_t> datagram(data + 1, size - 1);
  const DecodeResult r = Decode(datagram, receiver);
  if (!r.packet) return 0;
  std::vector<uint8_t> again;
  switch (r.packet->kind) {
    case PacketKind::kCommand:
      again = EncodeCommand(r.packet->command, receiver);
      break;
    case PacketKind::kState:
      again = EncodeState(r.packet->state, receiver);
      break;
    case PacketKind::kEndOfSession:
      again = EncodeEndOfSession(r.packet->sequence, r.packet->sender_time, receiver);
      break;
  }
  // the quaternions are read as they are sent, so every bit comes back.
  if (!std::equal(again.begin(), again.end(), datagram.begin(), datagram.end())) std::abort();
  return 0;
}
