#pragma once

/// @file
/// The viewer server's reading of an HTTP/1.x request head (viewer/viewer_server.hpp): where the
/// head ends in the bytes received, and its request line and the headers the server needs.
/// Strict: anything that is not a well-formed request line and header lines is invalid. Never
/// throws (other than std::bad_alloc), whatever the bytes.

#include <cstddef>
#include <string>
#include <string_view>

namespace graspsynth::viewer {

/// The end of the request head in `in` (just after its blank line), or std::string_view::npos
/// while the blank line has not come. Lines may end in CRLF or LF.
size_t HttpHeadEnd(std::string_view in);

/// A request head, as far as the server needs it.
struct HttpRequestHead {
  /// A request line METHOD SP TARGET SP HTTP/1.0|HTTP/1.1, with a token method, a target that
  /// starts with '/' and has only visible ASCII, and header lines NAME: VALUE with token names.
  bool valid = false;
  std::string method;
  std::string target;
  bool keep_alive = false;  ///< HTTP/1.1 without "Connection: close", or "keep-alive"
  bool has_body = false;    ///< a non-zero Content-Length or a Transfer-Encoding
};

/// Parses a request head (the bytes up to HttpHeadEnd).
HttpRequestHead ParseHttpRequestHead(std::string_view head);

}  // namespace graspsynth::viewer
