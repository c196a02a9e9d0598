#pragma once

/// @file
/// Where the shipped data (models/, learning_data/) is found at run time, and how outputs name
/// its files.

#include <filesystem>
#include <string>

namespace graspsynth {

/// $GRASPSYNTH_DATA_DIR when set and not empty, else the source checkout graspsynth was built
/// from. Files are looked up below it with the repository's layout (models/scene.json, ...).
std::filesystem::path DataDirectory();

/// How outputs name a file or folder of the shipped data that a default chose (such as
/// DefaultDemoDirectory()): relative to DataDirectory(), in '/' form ("learning_data/demos"),
/// so that results are the same bytes on every clone; a `path` that is not below
/// DataDirectory() (or a relative one) as it is. Lexical: no file is looked at. For defaults
/// only: a path the user gave is recorded as given.
std::string DataRelativeName(const std::filesystem::path& path);

}  // namespace graspsynth
