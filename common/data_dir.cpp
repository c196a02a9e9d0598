#include "common/data_dir.hpp"

#include <cstdlib>

namespace graspsynth {

std::filesystem::path DataDirectory() {
  const char* env = std::getenv("GRASPSYNTH_DATA_DIR");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(GRASPSYNTH_SOURCE_DIR);
}

std::string DataRelativeName(const std::filesystem::path& path) {
  std::filesystem::path root = DataDirectory().lexically_normal();
  if (!root.has_filename()) root = root.parent_path();  // "/opt/gs/" as "/opt/gs"
  if (path.is_relative() || root.is_relative()) return path.string();
  const std::filesystem::path relative = path.lexically_normal().lexically_relative(root);
  // empty: another root name; "..": outside.
  if (relative.empty() || *relative.begin() == "..") return path.string();
  std::string name = relative.generic_string();
  if (name.size() > 1 && name.back() == '/') name.pop_back();
  return name;
}

}  // namespace graspsynth
