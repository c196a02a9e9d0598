#pragma once

/// @file
/// The teleoperation loop's UDP socket (IPv4, POSIX): bound to an address and port, non-blocking,
/// it drains the datagrams that came in (bounded per call, so that a flood cannot stall the
/// control tick) and sends packets to a peer. A peer is an IPv4 address and port packed into a
/// uint64_t (PackPeer), the form TeleopSession's Datagram carries. Nothing is ever printed.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "teleop/teleop_session.hpp"

namespace graspsynth::teleop {

/// Packs an IPv4 address (host byte order) and a port into a peer id, and back.
uint64_t PackPeer(uint32_t address, uint16_t port);
uint32_t PeerAddress(uint64_t peer);
uint16_t PeerPort(uint64_t peer);
/// "a.b.c.d:port".
std::string PeerToString(uint64_t peer);
/// The peer id of a dotted-quad address and a port. Throws InputError naming the address when
/// it is not dotted-quad IPv4 or the port is outside 1..65535.
uint64_t ParsePeer(const std::string& address, int port);

/// Options of a UdpLink.
struct UdpLinkOptions {
  std::string address = "127.0.0.1";  ///< IPv4 address to bind; "0.0.0.0": every interface
  int port = 0;                       ///< UDP port; 0 picks any free one (UdpLink::port())
  /// At most this many datagrams are read per Receive() call; more wait in the socket's buffer
  /// (and the kernel drops what does not fit there).
  int max_datagrams_per_receive = 4096;
  /// Socket receive buffer asked for, bytes (the kernel may grant less).
  int receive_buffer_bytes = 1 << 20;
};

/// What a link has done.
struct UdpLinkCounters {
  uint64_t received = 0;       ///< datagrams read
  uint64_t oversized = 0;      ///< datagrams larger than any packet of the format (truncated)
  uint64_t sent = 0;           ///< datagrams sent
  uint64_t send_failures = 0;  ///< sends the system refused (e.g. a full buffer)
};

/// A bound UDP socket. Not thread-safe; movable, not copyable.
class UdpLink {
 public:
  /// Binds options.address:options.port. Throws InputError naming the address and the port
  /// with the system's reason when the address is not IPv4 or the port cannot be bound.
  explicit UdpLink(const UdpLinkOptions& options = {});
  ~UdpLink();
  UdpLink(UdpLink&& other) noexcept;
  UdpLink& operator=(UdpLink&& other) noexcept;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  /// The port bound (the chosen one when options.port was 0).
  int port() const { return port_; }

  /// Appends to `out` the datagrams waiting now (at most max_datagrams_per_receive), without
  /// blocking. Returns how many were appended.
  size_t Receive(std::vector<Datagram>* out);
  /// Waits up to timeout_s (s) for a datagram to arrive; true when one is waiting.
  bool WaitReadable(double timeout_s) const;
  /// Sends `bytes` to `peer`; false when the system refused (counted, never thrown).
  bool Send(std::span<const uint8_t> bytes, uint64_t peer);

  const UdpLinkCounters& counters() const { return counters_; }

 private:
  int fd_ = -1;
  int port_ = 0;
  int max_per_receive_ = 4096;
  UdpLinkCounters counters_;
};

}  // namespace graspsynth::teleop
