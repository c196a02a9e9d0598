#include "teleop/udp_link.hpp"

#include <gtest/gtest.h>

#include "common/errors.hpp"

namespace graspsynth::teleop {
namespace {

// receives until `count` datagrams came or a second passed.
std::vector<Datagram> ReceiveSome(UdpLink& link, size_t count) {
  std::vector<Datagram> in;
  for (int k = 0; k < 100 && in.size() < count; ++k) {
    link.WaitReadable(0.01);
    link.Receive(&in);
  }
  return in;
}

TEST(UdpLink, PeersPackAndParse) {
  const uint64_t peer = ParsePeer("127.0.0.1", 9870);
  EXPECT_EQ(PeerAddress(peer), 0x7F000001u);
  EXPECT_EQ(PeerPort(peer), 9870);
  EXPECT_EQ(PeerToString(peer), "127.0.0.1:9870");
  EXPECT_THROW(ParsePeer("localhost", 1), InputError);
  EXPECT_THROW(ParsePeer("127.0.0.1", 0), InputError);
}

TEST(UdpLink, SendsAndReceivesOverLoopbackWithTheSender) {
  UdpLink server;
  UdpLink client;
  EXPECT_GT(server.port(), 0);
  const std::vector<uint8_t> hello = {1, 2, 3, 4};
  ASSERT_TRUE(client.Send(hello, ParsePeer("127.0.0.1", server.port())));
  const std::vector<Datagram> in = ReceiveSome(server, 1);
  ASSERT_EQ(in.size(), 1u);
  EXPECT_EQ(in[0].bytes, hello);
  EXPECT_EQ(PeerPort(in[0].peer), client.port());
  // and back to the sender.
  ASSERT_TRUE(server.Send(hello, in[0].peer));
  EXPECT_EQ(ReceiveSome(client, 1).size(), 1u);
  EXPECT_EQ(server.counters().received, 1u);
  EXPECT_EQ(client.counters().sent, 1u);
}

TEST(UdpLink, BoundsTheDatagramsPerReceiveAndCutsOversizedOnes) {
  UdpLinkOptions options;
  options.max_datagrams_per_receive = 3;
  UdpLink server(options);
  UdpLink client;
  const uint64_t to = ParsePeer("127.0.0.1", server.port());
  for (int k = 0; k < 5; ++k) client.Send(std::vector<uint8_t>(8, k), to);
  client.Send(std::vector<uint8_t>(5000, 9), to);
  ASSERT_TRUE(server.WaitReadable(1.0));
  std::vector<Datagram> in;
  EXPECT_LE(server.Receive(&in), 3u);
  const std::vector<Datagram> rest = ReceiveSome(server, 6 - in.size());
  EXPECT_EQ(in.size() + rest.size(), 6u);
  EXPECT_EQ(server.counters().oversized, 1u);
  EXPECT_EQ(rest.back().bytes.size(), 2048u);
}

TEST(UdpLink, RefusesBadAddressesAndBusyPorts) {
  UdpLinkOptions bad;
  bad.address = "not an address";
  EXPECT_THROW(UdpLink{bad}, InputError);
  UdpLink first;
  UdpLinkOptions same;
  same.port = first.port();
  try {
    UdpLink second(same);
    FAIL() << "bound a port in use";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(std::to_string(first.port())), std::string::npos);
  }
}

}  // namespace
}  // namespace graspsynth::teleop
