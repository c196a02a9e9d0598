#pragma once

/// @file
/// Runs the graspsynth binary in a test, with text on its standard input, and captures what it
/// prints and its exit status.

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include "tests/utils/paths.hpp"

namespace graspsynth::testing {

struct CommandOutput {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string ReadFileText(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Runs `graspsynth <args>` (args are passed to the shell as written) with `input` on stdin.
/// With `timeout_s` > 0, under coreutils' `timeout` (a command still running then is killed and
/// exits 124): a guard against a hang, not a speed claim. With a `working_folder`, the command
/// runs there (relative paths in `args` are relative to it).
inline CommandOutput RunGraspsynth(const std::string& args, const std::string& input = "",
                                   int timeout_s = 0,
                                   const std::filesystem::path& working_folder = {}) {
  namespace fs = std::filesystem;
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir =
      fs::temp_directory_path() / ("graspsynth_cmd_" + std::string(info->test_suite_name()) + "_" +
                                   info->name() + "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "in") << input;
  const std::string guard =
      timeout_s > 0 ? "timeout -k 10 " + std::to_string(timeout_s) + " " : std::string();
  const std::string cd =
      working_folder.empty() ? std::string() : "cd '" + working_folder.string() + "' && ";
  const std::string command = cd + guard + ::testing::GraspsynthBinary() + " " + args + " < " +
                              (dir / "in").string() + " > " + (dir / "out").string() + " 2> " +
                              (dir / "err").string();
  const int status = std::system(command.c_str());
  CommandOutput result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadFileText(dir / "out");
  result.err = ReadFileText(dir / "err");
  fs::remove_all(dir);
  return result;
}

}  // namespace graspsynth::testing
