#pragma once

// Checks every request's option list must pass (tests/request/).

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <unistd.h>

#include "request/option.hpp"

namespace graspsynth::request {

// Every option has a name of its own, a help sentence, and a default that passes its own
// check (a default the front ends show and could not give back would be a trap).
template <class R>
void ExpectWellDescribed(const OptionList<R>& options) {
  const R defaults{};
  std::set<std::string> names, flags;
  for (const Option<R>& o : options) {
    EXPECT_TRUE(names.insert(o.info.name).second) << o.info.name;
    EXPECT_TRUE(flags.insert(o.info.Flag(o.get(defaults))).second) << o.info.name;
    EXPECT_FALSE(o.info.help.empty()) << o.info.name;
    if (!o.info.required) {
      EXPECT_EQ(CheckValue(o.info, o.get(defaults)), "") << o.info.name;
      R copy{};
      EXPECT_NO_THROW(Apply(o, o.get(defaults), o.info.name, &copy)) << o.info.name;
    }
  }
}

// Writes `text` to a file of the temporary folder, named after this process and `name` (the
// tests run in parallel), and returns its path.
inline std::filesystem::path WriteConfig(const std::string& name, const std::string& text) {
  const std::filesystem::path path = std::filesystem::path(::testing::TempDir()) /
                                     ("graspsynth_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace graspsynth::request
