#include "teleop/udp_link.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/errors.hpp"

namespace graspsynth::teleop {
namespace {

// larger than any packet of the format (a command is 216 bytes): a bigger datagram is cut here
// and then fails its length check.
constexpr size_t kMaxDatagramBytes = 2048;

sockaddr_in ToSockaddr(uint64_t peer) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(PeerAddress(peer));
  a.sin_port = htons(PeerPort(peer));
  return a;
}

}  // namespace

uint64_t PackPeer(uint32_t address, uint16_t port) {
  return (static_cast<uint64_t>(address) << 16) | port;
}
uint32_t PeerAddress(uint64_t peer) { return static_cast<uint32_t>(peer >> 16); }
uint16_t PeerPort(uint64_t peer) { return static_cast<uint16_t>(peer & 0xFFFFu); }

std::string PeerToString(uint64_t peer) {
  const uint32_t a = PeerAddress(peer);
  return std::to_string(a >> 24) + "." + std::to_string((a >> 16) & 0xFF) + "." +
         std::to_string((a >> 8) & 0xFF) + "." + std::to_string(a & 0xFF) + ":" +
         std::to_string(PeerPort(peer));
}

uint64_t ParsePeer(const std::string& address, int port) {
  in_addr a{};
  if (inet_pton(AF_INET, address.c_str(), &a) != 1) {
    throw InputError("address \"" + address + "\" is not an IPv4 dotted-quad address");
  }
  if (port < 1 || port > 65535) {
    throw InputError("port " + std::to_string(port) + " is outside 1..65535");
  }
  return PackPeer(ntohl(a.s_addr), static_cast<uint16_t>(port));
}

UdpLink::UdpLink(const UdpLinkOptions& options)
    : max_per_receive_(options.max_datagrams_per_receive) {
  const std::string where = options.address + ":" + std::to_string(options.port);
  if (options.port < 0 || options.port > 65535) {
    throw InputError("UDP port " + std::to_string(options.port) + " is outside 0..65535");
  }
  if (options.max_datagrams_per_receive < 1) {
    throw InputError("max_datagrams_per_receive must be positive");
  }
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(options.port));
  if (inet_pton(AF_INET, options.address.c_str(), &a.sin_addr) != 1) {
    throw InputError("address \"" + options.address + "\" is not an IPv4 dotted-quad address");
  }
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw InputError("cannot open a UDP socket: " + std::string(std::strerror(errno)));
  const int buffer = options.receive_buffer_bytes;
  ::setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &buffer, sizeof(buffer));  // best effort
  if (::bind(fd_, reinterpret_cast<const sockaddr*>(&a), sizeof(a)) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(fd_);
    fd_ = -1;
    throw InputError("cannot bind UDP " + where + ": " + reason);
  }
  socklen_t length = sizeof(a);
  ::getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &length);
  port_ = ntohs(a.sin_port);
}

UdpLink::~UdpLink() {
  if (fd_ >= 0) ::close(fd_);
}

UdpLink::UdpLink(UdpLink&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      port_(other.port_),
      max_per_receive_(other.max_per_receive_),
      counters_(other.counters_) {}

UdpLink& UdpLink::operator=(UdpLink&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = std::exchange(other.fd_, -1);
    port_ = other.port_;
    max_per_receive_ = other.max_per_receive_;
    counters_ = other.counters_;
  }
  return *this;
}

size_t UdpLink::Receive(std::vector<Datagram>* out) {
  size_t count = 0;
  uint8_t buffer[kMaxDatagramBytes];
  while (count < static_cast<size_t>(max_per_receive_)) {
    sockaddr_in from{};
    socklen_t length = sizeof(from);
    const ssize_t n = ::recvfrom(fd_, buffer, sizeof(buffer), MSG_TRUNC,
                                 reinterpret_cast<sockaddr*>(&from), &length);
    if (n < 0) {
      if (errno == EINTR) continue;
      break;  // EAGAIN: nothing more waiting (other errors: try again next tick)
    }
    Datagram d;
    const size_t kept = std::min(static_cast<size_t>(n), sizeof(buffer));
    if (static_cast<size_t>(n) > sizeof(buffer)) ++counters_.oversized;
    d.bytes.assign(buffer, buffer + kept);
    d.peer = PackPeer(ntohl(from.sin_addr.s_addr), ntohs(from.sin_port));
    out->push_back(std::move(d));
    ++counters_.received;
    ++count;
  }
  return count;
}

bool UdpLink::WaitReadable(double timeout_s) const {
  pollfd p{fd_, POLLIN, 0};
  const int ms = static_cast<int>(std::ceil(std::max(0.0, timeout_s) * 1e3));
  return ::poll(&p, 1, ms) > 0 && (p.revents & POLLIN);
}

bool UdpLink::Send(std::span<const uint8_t> bytes, uint64_t peer) {
  const sockaddr_in to = ToSockaddr(peer);
  const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), 0,
                             reinterpret_cast<const sockaddr*>(&to), sizeof(to));
  if (n != static_cast<ssize_t>(bytes.size())) {
    ++counters_.send_failures;
    return false;
  }
  ++counters_.sent;
  return true;
}

}  // namespace graspsynth::teleop
