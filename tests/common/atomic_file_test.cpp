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

}  // namespace
}  // namespace graspsynth
