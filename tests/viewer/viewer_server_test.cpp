#include "viewer/viewer_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <memory>
#include <thread>
#include <vector>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"

namespace graspsynth::viewer {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

// A connected client socket with a receive timeout, closed on destruction.
class Client {
 public:
  explicit Client(int port) {
    fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    timeval timeout{5, 0};
    ::setsockopt(fd_, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(static_cast<uint16_t>(port));
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) == 0;
  }
  ~Client() { ::close(fd_); }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  bool connected() const { return connected_; }
  int fd() const { return fd_; }
  void Send(const std::string& bytes) {
    ASSERT_EQ(::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(bytes.size()));
  }
  // everything until the server closes the connection (or the 5 s timeout).
  std::string ReadAll() {
    std::string out;
    char buffer[65536];
    for (;;) {
      const ssize_t n = ::recv(fd_, buffer, sizeof(buffer), 0);
      if (n <= 0) return out;
      out.append(buffer, static_cast<size_t>(n));
    }
  }

 private:
  int fd_ = -1;
  bool connected_ = false;
};

// One request on its own connection (closed by the server after the answer).
std::string Get(int port, const std::string& path, const std::string& method = "GET") {
  Client client(port);
  EXPECT_TRUE(client.connected());
  client.Send(method + " " + path + " HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n");
  return client.ReadAll();
}

std::string Body(const std::string& response) {
  const size_t end = response.find("\r\n\r\n");
  return end == std::string::npos ? "" : response.substr(end + 4);
}

// A folder with a stand-in page and no three.js.
std::filesystem::path PageOnlyAssets() {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("graspsynth_viewer_assets_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "index.html") << "<html>stand-in page</html>";
  std::ofstream(dir / "viewer.js") << "// stand-in";
  return dir;
}

TEST(ViewerServer, ServesTheBuiltPageSceneAndThreeJs) {
  ViewerServer server(R"({"format":"graspsynth-viewer-scene/1"})");
  ASSERT_GT(server.port(), 0);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");

  const std::string page = Get(server.port(), "/");
  EXPECT_THAT(page, StartsWith("HTTP/1.1 200 OK\r\n"));
  EXPECT_THAT(page, HasSubstr("Content-Type: text/html"));
  EXPECT_THAT(Body(page), HasSubstr("<script type=\"module\" src=\"/viewer.js\">"));
  EXPECT_THAT(Body(page), HasSubstr("/three.module.js"));
  EXPECT_EQ(Get(server.port(), "/index.html"), page);
  EXPECT_THAT(Body(Get(server.port(), "/viewer.js")), HasSubstr("from 'three'"));

  const std::string scene = Get(server.port(), "/scene.json");
  EXPECT_THAT(scene, HasSubstr("Content-Type: application/json"));
  EXPECT_EQ(Body(scene), R"({"format":"graspsynth-viewer-scene/1"})");

  // three.js is vendored by scripts/setup.sh; without it the server says how to get it.
  const std::string three = Get(server.port(), "/three.module.js");
  if (server.missing_assets().empty()) {
    EXPECT_THAT(three, StartsWith("HTTP/1.1 200 OK\r\n"));
    EXPECT_THAT(Body(three), HasSubstr("three.core.js"));
  } else {
    EXPECT_THAT(three, StartsWith("HTTP/1.1 503"));
  }
}

TEST(ViewerServer, SaysHowToGetAMissingThreeJs) {
  ViewerServerOptions options;
  options.asset_dir = PageOnlyAssets();
  ViewerServer server("{}", options);
  EXPECT_EQ(server.missing_assets().size(), 3u);
  EXPECT_EQ(Body(Get(server.port(), "/")), "<html>stand-in page</html>");
  const std::string three = Get(server.port(), "/three.module.js");
  EXPECT_THAT(three, StartsWith("HTTP/1.1 503 Service Unavailable\r\n"));
  EXPECT_THAT(Body(three), HasSubstr("scripts/setup.sh"));
  EXPECT_THAT(Body(three), HasSubstr("npm ci --prefix viewer"));
  std::filesystem::remove_all(options.asset_dir);
}

TEST(ViewerServer, FrameIsTheLatestPublished) {
  ViewerServer server("{}");
  EXPECT_THAT(Get(server.port(), "/frame"), StartsWith("HTTP/1.1 204 No Content\r\n"));
  server.Publish(R"({"t":1})");
  server.Publish(R"({"t":2})");
  const std::string frame = Get(server.port(), "/frame");
  EXPECT_THAT(frame, StartsWith("HTTP/1.1 200 OK\r\n"));
  EXPECT_THAT(frame, HasSubstr("Cache-Control: no-store"));
  EXPECT_EQ(Body(frame), R"({"t":2})");
  EXPECT_EQ(Body(Get(server.port(), "/frame?nocache=17")), R"({"t":2})");
  EXPECT_EQ(server.counters().frame_requests, 2u);
}

TEST(ViewerServer, KeepsConnectionsAliveAndAnswersPipelinedRequestsInOrder) {
  ViewerServer server("{\"scene\":1}");
  server.Publish("{\"frame\":1}");
  Client client(server.port());
  client.Send(
      "GET /frame HTTP/1.1\r\nHost: x\r\n\r\nGET /scene.json HTTP/1.1\r\n\r\n"
      "GET /frame HTTP/1.1\r\nConnection: close\r\n\r\n");
  const std::string all = client.ReadAll();
  const size_t first = all.find("{\"frame\":1}");
  const size_t second = all.find("{\"scene\":1}");
  const size_t third = all.find("{\"frame\":1}", first + 1);
  EXPECT_NE(first, std::string::npos);
  EXPECT_LT(first, second);
  EXPECT_LT(second, third);
  EXPECT_NE(third, std::string::npos);
  EXPECT_EQ(server.counters().connections, 1u);
}

TEST(ViewerServer, GarbageGets400AndTheServerKeepsServing) {
  ViewerServer server("{}");
  const std::string garbage[] = {
      "GARBAGE\r\n\r\n",
      std::string("\x16\x03\x01\x02\x00\x01\x00\x01\xfc\x03\x03\r\n\r\n", 15),  // a TLS hello
      "GET /frame HTTP/9.9\r\n\r\n",
      "GET frame HTTP/1.1\r\n\r\n",
      "GET /fr ame HTTP/1.1\r\n\r\n",
      "GET /frame HTTP/1.1\r\nno colon here\r\n\r\n",
      "GET /frame HTTP/1.1\r\nContent-Length: 5\r\n\r\nhello",
      "\r\n\r\n",
  };
  for (const std::string& request : garbage) {
    Client client(server.port());
    client.Send(request);
    EXPECT_THAT(client.ReadAll(), StartsWith("HTTP/1.1 400 Bad Request\r\n")) << request;
  }
  EXPECT_EQ(server.counters().bad_requests, std::size(garbage));
  EXPECT_THAT(Get(server.port(), "/"), StartsWith("HTTP/1.1 200 OK\r\n"));
}

TEST(ViewerServer, UnknownPathsAre404AndOtherMethods405) {
  ViewerServer server("{}");
  for (const char* path :
       {"/nope", "/../etc/passwd", "/frame/", "/favicon.ico", "/viewer.js.map"}) {
    const std::string response = Get(server.port(), path);
    EXPECT_THAT(response, StartsWith("HTTP/1.1 404 Not Found\r\n")) << path;
  }
  const std::string post = Get(server.port(), "/frame", "POST");
  EXPECT_THAT(post, StartsWith("HTTP/1.1 405 Method Not Allowed\r\n"));
  EXPECT_THAT(post, HasSubstr("Allow: GET, HEAD"));
  // HEAD: the headers of GET, no body.
  const std::string head = Get(server.port(), "/scene.json", "HEAD");
  EXPECT_THAT(head, StartsWith("HTTP/1.1 200 OK\r\n"));
  EXPECT_THAT(head, HasSubstr("Content-Length: 2\r\n"));
  EXPECT_EQ(Body(head), "");
}

TEST(ViewerServer, DropsOversizedRequests) {
  ViewerServerOptions options;
  options.max_request_bytes = 1024;
  ViewerServer server("{}", options);
  Client client(server.port());
  client.Send("GET / HTTP/1.1\r\nX-Filler: " + std::string(4000, 'a'));
  const std::string answer = client.ReadAll();  // 431, then closed (never the page)
  EXPECT_THAT(answer, StartsWith("HTTP/1.1 431"));
  EXPECT_THAT(Get(server.port(), "/scene.json"), StartsWith("HTTP/1.1 200 OK\r\n"));
}

TEST(ViewerServer, AnIdleConnectionDoesNotHoldOthersUp) {
  ViewerServer server("{}");
  Client idle(server.port());  // connects, sends nothing (as browsers' preconnects do)
  ASSERT_TRUE(idle.connected());
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THAT(Get(server.port(), "/scene.json"), StartsWith("HTTP/1.1 200 OK\r\n"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
}

// 200 clients that send half a request and stop (more than max_connections) cannot starve a
// normal client: new connections take the places of the silent ones.
TEST(ViewerServer, HalfOpenClientsDoNotStarveANormalRequest) {
  ViewerServer server("{}");
  std::vector<std::unique_ptr<Client>> slow;
  for (int i = 0; i < 200; ++i) {
    slow.push_back(std::make_unique<Client>(server.port()));
    ASSERT_TRUE(slow.back()->connected());
    slow.back()->Send("GET /index.html HTTP/1.1\r\nHost: loc");
  }
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THAT(Get(server.port(), "/scene.json"), StartsWith("HTTP/1.1 200 OK\r\n"));
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(1));
  EXPECT_GE(server.counters().evicted, 200u - 64u);
}

// A client that trickles its request, a byte at a time, is closed at the request deadline,
// although it is never idle.
TEST(ViewerServer, ARequestThatTricklesInIsClosedAtItsDeadline) {
  ViewerServerOptions options;
  options.request_timeout_s = 0.3;
  ViewerServer server("{}", options);
  Client trickle(server.port());
  ASSERT_TRUE(trickle.connected());
  const std::string request = "GET /scene.json HTTP/1.1\r\nHost: localhost\r\n\r\n";
  const auto start = std::chrono::steady_clock::now();
  bool closed = false;
  for (size_t i = 0; i + 1 < request.size() && !closed; ++i) {
    closed = ::send(trickle.fd(), request.data() + i, 1, MSG_NOSIGNAL) != 1;
    std::this_thread::sleep_for(std::chrono::milliseconds(40));
  }
  EXPECT_EQ(trickle.ReadAll(), "");  // closed without an answer
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(3));
  EXPECT_EQ(server.counters().timed_out, 1u);
  options.request_timeout_s = 0.0;
  GS_EXPECT_THROW_WITH(ViewerServer("{}", options), InputError, "request_timeout_s");
}

TEST(ViewerServer, PublishesFromAnotherThreadWhileServing) {
  ViewerServer server("{}");
  server.Publish("{\"t\":0}");
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (int i = 1; !done; ++i) server.Publish("{\"t\":" + std::to_string(i) + "}");
  });
  std::vector<std::string> bodies;
  for (int i = 0; i < 50; ++i) bodies.push_back(Body(Get(server.port(), "/frame")));
  done = true;
  producer.join();
  // every answer is a whole frame, and frames never go back in time.
  int last = -1;
  for (const std::string& body : bodies) {
    ASSERT_THAT(body, StartsWith("{\"t\":"));
    ASSERT_EQ(body.back(), '}');
    const int t = std::stoi(body.substr(5));
    EXPECT_GE(t, last);
    last = t;
  }
  server.Stop();
  server.Stop();  // idempotent
}

TEST(ViewerServer, RejectsBadAddressesAndBusyPorts) {
  ViewerServerOptions options;
  options.address = "localhost";
  GS_EXPECT_THROW_WITH(ViewerServer("{}", options), InputError, "'localhost'", "IPv4");
  options.address = "127.0.0.1";
  options.port = 70000;
  GS_EXPECT_THROW_WITH(ViewerServer("{}", options), InputError, "70000");
  const ViewerServer first("{}");
  options.port = first.port();
  GS_EXPECT_THROW_WITH(ViewerServer("{}", options), InputError,
                       "127.0.0.1:" + std::to_string(first.port()), "in use");
}

}  // namespace
}  // namespace graspsynth::viewer
