// The viewer server's request heads (viewer/http_request.hpp).
#include <cstdlib>

#include "fuzz/fuzz_support.hpp"
#include "viewer/http_request.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace graspsynth;
  const std::string_view in = fuzz::AsText(data, size);
  const size_t end = viewer::HttpHeadEnd(in);
  if (end != std::string_view::npos && end > in.size()) std::abort();
  const viewer::HttpRequestHead head =
      viewer::ParseHttpRequestHead(end == std::string_view::npos ? in : in.substr(0, end));
  // a valid request names a path of visible ASCII.
  if (head.valid && (head.target.empty() || head.target.front() != '/')) std::abort();
  return 0;
}
