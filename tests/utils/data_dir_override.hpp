#pragma once

/// @file
/// $GRASPSYNTH_DATA_DIR set for the scope of one test.

#include <cstdlib>
#include <optional>
#include <string>

namespace graspsynth::testing {

/// Sets $GRASPSYNTH_DATA_DIR (unsets it for nullptr) for the scope of one test and restores it
/// after.
class DataDirOverride {
 public:
  explicit DataDirOverride(const char* value) {
    if (const char* saved = std::getenv("GRASPSYNTH_DATA_DIR")) saved_ = saved;
    if (value) {
      setenv("GRASPSYNTH_DATA_DIR", value, 1);
    } else {
      unsetenv("GRASPSYNTH_DATA_DIR");
    }
  }
  ~DataDirOverride() {
    if (saved_) {
      setenv("GRASPSYNTH_DATA_DIR", saved_->c_str(), 1);
    } else {
      unsetenv("GRASPSYNTH_DATA_DIR");
    }
  }
  DataDirOverride(const DataDirOverride&) = delete;
  DataDirOverride& operator=(const DataDirOverride&) = delete;

 private:
  std::optional<std::string> saved_;
};

}  // namespace graspsynth::testing
