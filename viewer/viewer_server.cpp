#include "viewer/viewer_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>
#include <optional>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string_view>

#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/valid_options.hpp"
#include "viewer/http_request.hpp"

namespace graspsynth::viewer {
namespace {

using Clock = std::chrono::steady_clock;

// the files of the page, by the path they are served at.
struct AssetFile {
  const char* path;
  const char* file;
  const char* content_type;
  bool vendored;  // from three.js (npm), not from viewer/
};
constexpr AssetFile kAssetFiles[] = {
    {"/index.html", "index.html", "text/html; charset=utf-8", false},
    {"/viewer.js", "viewer.js", "text/javascript; charset=utf-8", false},
    {"/three.module.js", "three.module.js", "text/javascript; charset=utf-8", true},
    {"/three.core.js", "three.core.js", "text/javascript; charset=utf-8", true},
    {"/OrbitControls.js", "OrbitControls.js", "text/javascript; charset=utf-8", true},
};

std::string SystemError(const std::string& what) { return what + ": " + std::strerror(errno); }

std::shared_ptr<const std::string> ReadAsset(const std::filesystem::path& path) {
  try {
    return std::make_shared<const std::string>(ReadInputFile(path, input_kind::kViewerAsset));
  } catch (const InputError&) {
    return nullptr;
  }
}

const char* ReasonPhrase(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 204:
      return "No Content";
    case 400:
      return "Bad Request";
    case 404:
      return "Not Found";
    case 405:
      return "Method Not Allowed";
    case 431:
      return "Request Header Fields Too Large";
    case 503:
      return "Service Unavailable";
    default:
      return "Unknown";
  }
}

std::shared_ptr<const std::string> Text(std::string text) {
  return std::make_shared<const std::string>(std::move(text) + "\n");
}

}  // namespace

std::filesystem::path DefaultViewerAssetDirectory() { return GRASPSYNTH_VIEWER_DIR; }

bool ViewerServerOptions::IsValid(std::string* why) const {
  std::string reason;
  if (address.empty()) {
    reason = "address is empty";
  } else if (port < 0 || port > 65535) {
    reason = "port " + std::to_string(port) + " is outside 0..65535";
  } else if (max_request_bytes < 64) {
    reason = "max_request_bytes " + std::to_string(max_request_bytes) + " is below 64";
  } else if (max_connections < 1) {
    reason = "max_connections " + std::to_string(max_connections) + " is not positive";
  } else if (!(idle_timeout_s > 0.0)) {
    reason = "idle_timeout_s " + std::to_string(idle_timeout_s) + " is not positive";
  } else if (!(request_timeout_s > 0.0)) {
    reason = "request_timeout_s " + std::to_string(request_timeout_s) + " is not positive";
  }
  if (why != nullptr) *why = reason;
  return reason.empty();
}

struct ViewerServer::Connection {
  int fd = -1;
  std::string in;                           // received, not yet answered
  std::string head;                         // response head being sent
  std::shared_ptr<const std::string> body;  // response body being sent (may be null)
  size_t sent = 0;                          // bytes of head + body sent
  bool close_after_write = false;
  Clock::time_point last_activity = Clock::now();
  Clock::time_point request_started;  // when the first byte of `in` arrived (if any)

  size_t pending() const { return head.size() + (body ? body->size() : 0) - sent; }
};

struct ViewerServer::Response {
  int status = 200;
  std::string content_type = "text/plain; charset=utf-8";
  std::shared_ptr<const std::string> body;
  bool close = false;
};

ViewerServer::ViewerServer(std::string scene_json, const ViewerServerOptions& options)
    : address_(options.address),
      options_(options),
      scene_(std::make_shared<const std::string>(std::move(scene_json))) {
  RequireValid(options, "viewer server");

  for (const AssetFile& file : kAssetFiles) {
    const std::filesystem::path path = options.asset_dir / file.file;
    Asset asset{file.content_type, ReadAsset(path), ""};
    if (!asset.body) {
      missing_assets_.push_back(path.string());
      asset.missing_message =
          file.vendored
              ? "graspsynth viewer: three.js is not vendored: " + path.string() +
                    " is missing. Run scripts/setup.sh (it runs 'npm ci --prefix viewer'), then "
                    "rebuild graspsynth: the build copies three.js into " +
                    options.asset_dir.string() + "."
              : "graspsynth viewer: " + path.string() +
                    " is missing. Rebuild graspsynth: the build copies viewer/ into " +
                    options.asset_dir.string() + ".";
    }
    assets_.emplace_back(file.path, std::move(asset));
  }

  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(options.port));
  if (inet_pton(AF_INET, options.address.c_str(), &addr.sin_addr) != 1) {
    throw InputError("viewer server: address '" + options.address +
                     "' is not an IPv4 address (e.g. 127.0.0.1)");
  }
  const std::string where = options.address + ":" + std::to_string(options.port);
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (listen_fd_ < 0) throw InputError(SystemError("viewer server: socket"));
  const int one = 1;
  ::setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
  if (::bind(listen_fd_, reinterpret_cast<const sockaddr*>(&addr), sizeof(addr)) != 0 ||
      ::listen(listen_fd_, SOMAXCONN) != 0) {
    const std::string message = SystemError("viewer server: cannot listen on " + where);
    ::close(listen_fd_);
    listen_fd_ = -1;
    throw InputError(message);
  }
  socklen_t length = sizeof(addr);
  ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&addr), &length);
  port_ = ntohs(addr.sin_port);
  if (::pipe2(wake_fds_, O_NONBLOCK | O_CLOEXEC) != 0) {
    const std::string message = SystemError("viewer server: pipe");
    ::close(listen_fd_);
    listen_fd_ = -1;
    throw InputError(message);
  }
  thread_ = std::thread([this] { Serve(); });
}

ViewerServer::~ViewerServer() { Stop(); }

std::string ViewerServer::url() const {
  const std::string host = address_ == "0.0.0.0" ? "127.0.0.1" : address_;
  return "http://" + host + ":" + std::to_string(port_) + "/";
}

void ViewerServer::Publish(std::string frame_json) {
  auto frame = std::make_shared<const std::string>(std::move(frame_json));
  const std::lock_guard<std::mutex> lock(frame_mutex_);
  frame_.swap(frame);
}

ViewerServerCounters ViewerServer::counters() const {
  const std::lock_guard<std::mutex> lock(counters_mutex_);
  return counters_;
}

void ViewerServer::Stop() {
  if (thread_.joinable()) {
    stopping_ = true;
    const char byte = 0;
    while (::write(wake_fds_[1], &byte, 1) < 0 && errno == EINTR) {
    }
    thread_.join();
  }
  for (int* fd : {&listen_fd_, &wake_fds_[0], &wake_fds_[1]}) {
    if (*fd >= 0) ::close(*fd);
    *fd = -1;
  }
}

void ViewerServer::Serve() {
  std::vector<Connection> connections;
  std::vector<pollfd> fds;
  char buffer[16384];
  while (!stopping_) {
    // wake pipe, listening socket, then one entry per connection (in order).
    fds.assign({{wake_fds_[0], POLLIN, 0}, {listen_fd_, POLLIN, 0}});
    for (const Connection& c : connections) {
      fds.push_back({c.fd, static_cast<short>(c.pending() > 0 ? POLLOUT : POLLIN), 0});
    }
    if (::poll(fds.data(), fds.size(), 200) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    if (fds[0].revents != 0) break;
    const size_t count = connections.size();
    for (size_t i = 0; i < count; ++i) {
      Connection& c = connections[i];
      const short events = fds[i + 2].revents;
      if (events == 0) continue;
      bool keep = true;
      try {
        if (c.pending() > 0) {
          // send what is left of the response; once it is out, answer what is queued.
          const size_t head_left = c.sent < c.head.size() ? c.head.size() - c.sent : 0;
          const char* data =
              head_left > 0 ? c.head.data() + c.sent : c.body->data() + (c.sent - c.head.size());
          const size_t size = head_left > 0 ? head_left : c.pending();
          const ssize_t n = ::send(c.fd, data, size, MSG_NOSIGNAL);
          if (n > 0) {
            c.sent += static_cast<size_t>(n);
            c.last_activity = Clock::now();
            if (c.pending() == 0) {
              keep = !c.close_after_write;
              if (keep) HandleInput(&c);
            }
          } else if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
            keep = false;
          } else if (events & (POLLERR | POLLHUP)) {
            keep = false;
          }
        } else {
          const ssize_t n = ::recv(c.fd, buffer, sizeof(buffer), 0);
          if (n > 0) {
            c.last_activity = Clock::now();
            if (c.in.empty()) c.request_started = c.last_activity;
            c.in.append(buffer, static_cast<size_t>(n));
            HandleInput(&c);
          } else if (n == 0 || (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
            keep = false;  // closed by the peer, or broken
          }
        }
      } catch (const std::exception&) {
        keep = false;  // out of memory while answering: drop this connection only
      }
      if (!keep) {
        ::close(c.fd);
        c.fd = -1;
      }
    }
    // idle connections (no request, or a reader that stopped reading) and requests that do
    // not arrive whole in time (a client that trickles bytes) are closed.
    const Clock::time_point now = Clock::now();
    const auto idle = std::chrono::duration<double>(options_.idle_timeout_s);
    const auto deadline = std::chrono::duration<double>(options_.request_timeout_s);
    for (Connection& c : connections) {
      if (c.fd < 0) continue;
      const bool late = c.pending() == 0 && !c.in.empty() && now - c.request_started > deadline;
      if (late || now - c.last_activity > idle) {
        ::close(c.fd);
        c.fd = -1;
        const std::lock_guard<std::mutex> lock(counters_mutex_);
        ++counters_.timed_out;
      }
    }
    std::erase_if(connections, [](const Connection& c) { return c.fd < 0; });
    if (fds[1].revents != 0) Accept(&connections);
  }
  for (const Connection& c : connections) ::close(c.fd);
}

void ViewerServer::Accept(std::vector<Connection>* connections) {
  for (;;) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) return;  // EAGAIN: none left (or a transient error: poll again)
    if (static_cast<int>(connections->size()) >= options_.max_connections) {
      // the new connection takes the place of the one that has been silent the longest; one
      // whose answer is being sent is kept.
      auto victim = connections->end();
      for (auto c = connections->begin(); c != connections->end(); ++c) {
        if (c->pending() == 0 &&
            (victim == connections->end() || c->last_activity < victim->last_activity)) {
          victim = c;
        }
      }
      const std::lock_guard<std::mutex> lock(counters_mutex_);
      if (victim == connections->end()) {
        ::close(fd);
        ++counters_.refused;
        continue;
      }
      ::close(victim->fd);
      connections->erase(victim);
      ++counters_.evicted;
    }
    Connection c;
    c.fd = fd;
    connections->push_back(std::move(c));
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.connections;
  }
}

void ViewerServer::HandleInput(Connection* c) {
  const size_t end = HttpHeadEnd(c->in);
  Response response;
  std::string method;
  if (end == std::string::npos) {
    if (c->in.size() <= options_.max_request_bytes) return;  // wait for the rest
    response = {431, "text/plain; charset=utf-8", Text("request head too large"), true};
  } else if (end > options_.max_request_bytes) {
    response = {431, "text/plain; charset=utf-8", Text("request head too large"), true};
  } else {
    const std::string head = c->in.substr(0, end);
    c->in.erase(0, end);
    c->request_started = Clock::now();  // a pipelined request's deadline starts now
    const HttpRequestHead request = ParseHttpRequestHead(head);
    method = request.method;
    const bool valid = request.valid, keep_alive = request.keep_alive, has_body = request.has_body;
    if (!valid) {
      response = {400, "text/plain; charset=utf-8", Text("malformed request"), true};
    } else if (has_body) {
      response = {400, "text/plain; charset=utf-8", Text("request bodies are not accepted"), true};
    } else if (method != "GET" && method != "HEAD") {
      response = {405, "text/plain; charset=utf-8", Text("only GET and HEAD"), !keep_alive};
    } else {
      response = Answer(request.target);
      response.close = !keep_alive;
    }
  }

  {
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.requests;
    if (response.status == 400 || response.status == 405 || response.status == 431) {
      ++counters_.bad_requests;
    }
  }
  const size_t length = response.body ? response.body->size() : 0;
  std::string head =
      "HTTP/1.1 " + std::to_string(response.status) + " " + ReasonPhrase(response.status) + "\r\n";
  if (response.status != 204) {
    head += "Content-Type: " + response.content_type +
            "\r\nContent-Length: " + std::to_string(length) + "\r\n";
  }
  if (response.status == 405) head += "Allow: GET, HEAD\r\n";
  head += "Cache-Control: no-store\r\nX-Content-Type-Options: nosniff\r\nConnection: ";
  head += response.close ? "close\r\n\r\n" : "keep-alive\r\n\r\n";
  c->head = std::move(head);
  c->body = method == "HEAD" || response.status == 204 ? nullptr : std::move(response.body);
  c->sent = 0;
  c->close_after_write = response.close;
  if (response.close) c->in.clear();
}

ViewerServer::Response ViewerServer::Answer(const std::string& target) {
  const std::string path = target.substr(0, target.find_first_of("?#"));
  Response response;
  if (path == "/frame") {
    {
      const std::lock_guard<std::mutex> lock(frame_mutex_);
      response.body = frame_;
    }
    if (!response.body) {
      response.status = 204;
      return response;
    }
    response.content_type = "application/json";
    const std::lock_guard<std::mutex> lock(counters_mutex_);
    ++counters_.frame_requests;
    return response;
  }
  if (path == "/scene.json") {
    response.content_type = "application/json";
    response.body = scene_;
    return response;
  }
  const std::string asset_path = path == "/" ? "/index.html" : path;
  for (const auto& [served_at, asset] : assets_) {
    if (served_at != asset_path) continue;
    if (!asset.body) {
      response.status = 503;
      response.body = Text(asset.missing_message);
      return response;
    }
    response.content_type = asset.content_type;
    response.body = asset.body;
    return response;
  }
  response.status = 404;
  response.body = Text("not found: " + path);
  return response;
}

}  // namespace graspsynth::viewer
