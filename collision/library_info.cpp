#include "collision/library_info.hpp"

#include <fcl/config.h>

namespace graspsynth {

std::string CollisionLibraryInfo() { return std::string("FCL ") + FCL_VERSION; }

}  // namespace graspsynth
