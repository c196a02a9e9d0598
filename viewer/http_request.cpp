#include "viewer/http_request.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <vector>

namespace graspsynth::viewer {
namespace {

std::string Lowercase(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// RFC 9110 token characters (method and header names).
bool IsToken(std::string_view text) {
  if (text.empty()) return false;
  return std::all_of(text.begin(), text.end(), [](unsigned char c) {
    return std::isalnum(c) || std::strchr("!#$%&'*+-.^_`|~", c) != nullptr;
  });
}

std::vector<std::string_view> HeadLines(std::string_view head) {
  std::vector<std::string_view> lines;
  while (!head.empty()) {
    const size_t eol = head.find('\n');
    std::string_view line = head.substr(0, eol);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (eol == std::string_view::npos) break;
    head.remove_prefix(eol + 1);
  }
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  return lines;
}

std::string_view TrimSpaces(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) text.remove_prefix(1);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.remove_suffix(1);
  return text;
}

}  // namespace

size_t HttpHeadEnd(std::string_view in) {
  for (size_t i = in.find('\n'); i != std::string_view::npos; i = in.find('\n', i + 1)) {
    if (i + 1 < in.size() && in[i + 1] == '\n') return i + 2;
    if (i + 2 < in.size() && in[i + 1] == '\r' && in[i + 2] == '\n') return i + 3;
  }
  return std::string_view::npos;
}

HttpRequestHead ParseHttpRequestHead(std::string_view head) {
  HttpRequestHead request;
  const std::vector<std::string_view> lines = HeadLines(head);
  std::string_view version;
  bool valid = !lines.empty();
  if (valid) {
    const std::string_view line = lines[0];
    const size_t a = line.find(' ');
    const size_t b = a == std::string_view::npos ? a : line.find(' ', a + 1);
    valid = b != std::string_view::npos && line.find(' ', b + 1) == std::string_view::npos;
    if (valid) {
      const std::string_view method = line.substr(0, a);
      const std::string_view target = line.substr(a + 1, b - a - 1);
      version = line.substr(b + 1);
      valid = IsToken(method) && (version == "HTTP/1.1" || version == "HTTP/1.0") &&
              !target.empty() && target.front() == '/' &&
              std::none_of(target.begin(), target.end(),
                           [](unsigned char ch) { return ch <= 0x20 || ch >= 0x7f; });
      request.method = method;
      request.target = target;
    }
  }
  request.keep_alive = version == "HTTP/1.1";
  for (size_t i = 1; valid && i < lines.size(); ++i) {
    const size_t colon = lines[i].find(':');
    if (colon == std::string_view::npos || !IsToken(lines[i].substr(0, colon))) {
      valid = false;
      break;
    }
    const std::string name = Lowercase(lines[i].substr(0, colon));
    const std::string value = Lowercase(TrimSpaces(lines[i].substr(colon + 1)));
    if (name == "connection") {
      if (value.find("close") != std::string::npos) request.keep_alive = false;
      if (value.find("keep-alive") != std::string::npos) request.keep_alive = true;
    } else if ((name == "content-length" && value != "0") || name == "transfer-encoding") {
      request.has_body = true;
    }
  }
  request.valid = valid;
  return request;
}

}  // namespace graspsynth::viewer
