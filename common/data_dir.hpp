#pragma once

/// @file
/// Where the shipped data (models/, learning_data/) is found at run time.

#include <filesystem>

namespace graspsynth {

/// $GRASPSYNTH_DATA_DIR when set and not empty, else the source checkout graspsynth was built
/// from. Files are looked up below it with the repository's layout (models/scene.json, ...).
std::filesystem::path DataDirectory();

}  // namespace graspsynth
