#include "common/atomic_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/errors.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

std::string ReadAll(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(WriteFileAtomically, WritesReplacesAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / "graspsynth_atomic_test";
  fs::remove_all(dir);
  const fs::path file = dir / "sub" / "out.json";
  WriteFileAtomically(file, "first");
  EXPECT_EQ(ReadAll(file), "first");
  WriteFileAtomically(file, "second");
  EXPECT_EQ(ReadAll(file), "second");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "sub")) ++entries;
  EXPECT_EQ(entries, 1);
  fs::remove_all(dir);
}

TEST(WriteFileAtomically, ThrowsNamingAnUnwritablePath) {
  // a regular file cannot be a folder.
  const fs::path blocker = fs::temp_directory_path() / "graspsynth_atomic_blocker";
  WriteFileAtomically(blocker, "x");
  EXPECT_THROW(WriteFileAtomically(blocker / "out.json", "y"), InputError);
  fs::remove(blocker);
}

TEST(CreateOwnerOnlyFileAtomically, CreatesOwnerOnlyNeverReplacesAndLeavesNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / "graspsynth_atomic_owner_test";
  fs::remove_all(dir);
  const fs::path file = dir / "sub" / "secret.key";
  CreateOwnerOnlyFileAtomically(file, "first");
  EXPECT_EQ(ReadAll(file), "first");
  EXPECT_EQ(fs::status(file).permissions(), fs::perms::owner_read | fs::perms::owner_write);
  try {
    CreateOwnerOnlyFileAtomically(file, "second");
    ADD_FAILURE() << "replaced an existing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + "' exists"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(ReadAll(file), "first");
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir / "sub")) ++entries;
  EXPECT_EQ(entries, 1);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace graspsynth
