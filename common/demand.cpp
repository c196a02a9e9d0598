#include "common/demand.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

namespace graspsynth::internal {

void DemandFailed(std::string_view condition, std::string_view message, std::string_view file,
                  int line) {
  const std::string text = std::string(file) + ":" + std::to_string(line) +
                           ": graspsynth invariant failed: " + std::string(condition) + " (" +
                           std::string(message) + ")\n";
  std::fputs(text.c_str(), stderr);
  std::abort();
}

}  // namespace graspsynth::internal
