#pragma once

/// @file
/// The viewer's web server: a small HTTP/1.1 server on POSIX sockets, one thread, that serves
/// the browser viewer (viewer/index.html, viewer/viewer.js and the vendored three.js) with the
/// scene document and the latest frame of viewer/viewer_scene.hpp. A producer (the replay of
/// `graspsynth view`, the live teleoperation loop) calls Publish() once per control tick; the
/// page polls /frame once per animation frame and draws what it gets.
///
/// Paths (GET or HEAD; a query string is ignored):
///
///   /, /index.html      the page
///   /viewer.js          the page's script (an ES module)
///   /three.module.js    three.js, vendored from viewer/node_modules (with /three.core.js, the
///                       core it imports, and /OrbitControls.js, the camera controls)
///   /scene.json         the scene document given to the constructor
///   /frame              the latest published frame (JSON); 204 before the first
///
/// Anything else is 404; another method 405; only these paths are served, never a file named by
/// the request. A request line or header that does not parse is 400 and the connection is
/// closed; a request head longer than max_request_bytes, or a request with a body, is dropped
/// (the connection is closed, with a 431 or 400 when it can be sent). Connections are kept
/// alive (HTTP/1.1) and closed after idle_timeout_s without a request. A vendored file that is
/// missing is answered with 503 and a text that says how to get it. Nothing is ever printed:
/// the owner reads missing_assets() and the counters.
///
/// Slow and hostile clients cannot starve a normal one: a request head must arrive whole within
/// request_timeout_s of its first byte (a client that trickles bytes is closed), and when
/// max_connections are open a new connection takes the place of the one that has been silent
/// the longest (never one whose answer is being sent).

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace graspsynth::viewer {

/// The folder the build copies the viewer's files into (viewer/*.html, viewer/*.js and three.js
/// from viewer/node_modules): `<build>/viewer_assets`, fixed at configure time.
std::filesystem::path DefaultViewerAssetDirectory();

/// Options of ViewerServer.
struct ViewerServerOptions {
  /// IPv4 address to listen on. The default accepts only this machine; "0.0.0.0" opens the
  /// viewer to the network (there is no authentication).
  std::string address = "127.0.0.1";
  /// TCP port; 0 picks any free port (ViewerServer::port() tells which).
  int port = 0;
  /// Folder with index.html, viewer.js, three.module.js, three.core.js, OrbitControls.js.
  std::filesystem::path asset_dir = DefaultViewerAssetDirectory();
  /// A request line with its headers longer than this (bytes) is dropped.
  size_t max_request_bytes = 8192;
  /// At most this many connections at once; more are closed as they come.
  int max_connections = 64;
  /// A connection without a complete request for this long (s) is closed.
  double idle_timeout_s = 10.0;
  /// A request head not complete this long (s) after its first byte is dropped (closed).
  double request_timeout_s = 2.0;

  /// False (and why) when the port is outside 0..65535, a limit or a timeout is not positive
  /// or the address is empty.
  bool IsValid(std::string* why) const;
};

/// What the server has done, for the owner's report.
struct ViewerServerCounters {
  uint64_t connections = 0;     ///< accepted
  uint64_t requests = 0;        ///< answered, any status
  uint64_t frame_requests = 0;  ///< answered on /frame with a frame (200)
  uint64_t bad_requests = 0;    ///< 400, 405 or 431, or dropped for their size
  uint64_t timed_out = 0;       ///< closed: idle, or a request head not complete in time
  uint64_t evicted = 0;         ///< closed to make room for a new connection
  uint64_t refused = 0;         ///< new connections closed: every open one was being answered
};

/// The server. Construction binds and starts the thread; destruction stops it.
class ViewerServer {
 public:
  /// Reads the page and three.js from options.asset_dir (a missing vendored file is listed in
  /// missing_assets() and answered with 503), binds options.address:options.port, listens and
  /// starts the serving thread. `scene_json` is served as /scene.json. Throws InputError for
  /// invalid options, an address that is not IPv4 dotted-quad, or a port that cannot be bound
  /// (naming the address, the port and the system's reason).
  explicit ViewerServer(std::string scene_json, const ViewerServerOptions& options = {});
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  /// The port listened on (the chosen one when options.port was 0).
  int port() const { return port_; }
  /// "http://ADDRESS:PORT/" (with 127.0.0.1 for a server bound to 0.0.0.0).
  std::string url() const;
  /// File names of the viewer's files that were not found in asset_dir, with the folder.
  const std::vector<std::string>& missing_assets() const { return missing_assets_; }

  /// Makes `frame_json` (one JSON document, normally ViewerFrameJson) the answer of /frame.
  /// Thread-safe and cheap (a pointer swap); may be called at any rate from any thread.
  void Publish(std::string frame_json);

  /// A snapshot of the counters (thread-safe).
  ViewerServerCounters counters() const;

  /// Stops the thread and closes every socket. Idempotent; called by the destructor.
  void Stop();

 private:
  struct Asset {
    std::string content_type;
    std::shared_ptr<const std::string> body;  // null when the file is missing
    std::string missing_message;
  };
  struct Connection;
  struct Response;

  void Serve();
  void Accept(std::vector<Connection>* connections);
  // answers the first complete request of the connection's input (sets its response); does
  // nothing while the request is incomplete and within the size limit.
  void HandleInput(Connection* connection);
  Response Answer(const std::string& target);

  std::string address_;
  int port_ = 0;
  ViewerServerOptions options_;
  std::vector<std::pair<std::string, Asset>> assets_;  // by path
  std::shared_ptr<const std::string> scene_;
  std::vector<std::string> missing_assets_;

  mutable std::mutex frame_mutex_;
  std::shared_ptr<const std::string> frame_;

  mutable std::mutex counters_mutex_;
  ViewerServerCounters counters_;

  int listen_fd_ = -1;
  int wake_fds_[2] = {-1, -1};  // a pipe: Stop() writes a byte to wake poll()
  std::atomic<bool> stopping_{false};
  std::thread thread_;
};

}  // namespace graspsynth::viewer
