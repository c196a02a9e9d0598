#pragma once

#include <string>

namespace graspsynth {

/// Version of the FCL library the collision module was built against, e.g. "FCL 0.7.0".
std::string CollisionLibraryInfo();

}  // namespace graspsynth
