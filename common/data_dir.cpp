#include "common/data_dir.hpp"

#include <cstdlib>

namespace graspsynth {

std::filesystem::path DataDirectory() {
  const char* env = std::getenv("GRASPSYNTH_DATA_DIR");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(GRASPSYNTH_SOURCE_DIR);
}

}  // namespace graspsynth
