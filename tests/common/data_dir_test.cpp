// Tests of the data directory and of how outputs name its files: relative to it, so that the
// results of the shipped defaults are the same bytes on every clone; other paths as given.

#include "common/data_dir.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "tests/utils/data_dir_override.hpp"
#include "tests/utils/paths.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

using testing::DataDirOverride;

TEST(DataRelativeName, AFileBelowTheDataDirectoryIsNamedRelativeToIt) {
  for (const char* root : {"/opt/gs", "/opt/gs/", "/opt/./gs"}) {
    SCOPED_TRACE(root);
    const DataDirOverride data(root);
    EXPECT_EQ(DataRelativeName("/opt/gs/learning_data/demos"), "learning_data/demos");
    EXPECT_EQ(DataRelativeName("/opt/gs/learning_data/demos/"), "learning_data/demos");
    EXPECT_EQ(DataRelativeName(fs::path("/opt/gs") / "models" / "scene.json"), "models/scene.json");
    EXPECT_EQ(DataRelativeName("/opt/gs/learning_data/../models/./scene.json"),
              "models/scene.json");
    EXPECT_EQ(DataRelativeName("/opt/gs"), ".");
  }
}

TEST(DataRelativeName, AnyOtherPathIsKeptAsGiven) {
  const DataDirOverride data("/opt/gs");
  // outside, or a sibling whose name starts with the data directory's.
  EXPECT_EQ(DataRelativeName("/opt/other/demos"), "/opt/other/demos");
  EXPECT_EQ(DataRelativeName("/opt/gsx/learning_data/demos"), "/opt/gsx/learning_data/demos");
  EXPECT_EQ(DataRelativeName("/opt/gs/../other/./demos"), "/opt/gs/../other/./demos");
  EXPECT_EQ(DataRelativeName("/opt"), "/opt");
  // relative paths are the user's: relative to the working folder, not to the data directory.
  EXPECT_EQ(DataRelativeName("learning_data/demos"), "learning_data/demos");
  EXPECT_EQ(DataRelativeName("../gs/./demos"), "../gs/./demos");
  EXPECT_EQ(DataRelativeName(""), "");
}

TEST(DataRelativeName, ARelativeDataDirectoryNamesNothingRelativeToIt) {
  const DataDirOverride data("data");
  EXPECT_EQ(DataDirectory(), fs::path("data"));
  EXPECT_EQ(DataRelativeName("data/learning_data/demos"), "data/learning_data/demos");
  EXPECT_EQ(DataRelativeName("/abs/learning_data/demos"), "/abs/learning_data/demos");
}

TEST(DataRelativeName, TheBuiltInDataDirectoryIsTheClone) {
  const DataDirOverride data(nullptr);
  EXPECT_EQ(DataDirectory(), fs::path(::testing::SourceDir()));
  EXPECT_EQ(DataRelativeName(DataDirectory() / "learning_data" / "demos"), "learning_data/demos");
  const DataDirOverride empty("");
  EXPECT_EQ(DataDirectory(), fs::path(::testing::SourceDir()));
}

}  // namespace
}  // namespace graspsynth
