#pragma once

/// @file
/// Where the tests find the clone's shipped files and the built command. The paths are compiled
/// into paths.cpp alone, so that no other test object depends on where the clone is.

namespace testing {

/// The repository root, absolute.
const char* SourceDir();
/// The built `graspsynth` command, absolute.
const char* GraspsynthBinary();

}  // namespace testing

// the same names inside graspsynth, where graspsynth::testing (eigen_matchers.hpp) hides ::testing.
namespace graspsynth::testing {
using ::testing::GraspsynthBinary;
using ::testing::SourceDir;
}  // namespace graspsynth::testing
