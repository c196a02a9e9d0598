#include "learning_data/demo_directory.hpp"

#include <algorithm>
#include <system_error>

#include "common/data_dir.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"

namespace graspsynth {

namespace fs = std::filesystem;

DemoDirectory ReadDemoDirectory(const fs::path& directory, const std::string& name) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec)) {
    throw InputError("demonstration folder '" + directory.string() +
                     "' does not exist or is not a folder");
  }
  std::vector<fs::path> files;
  fs::directory_iterator it(directory, ec);
  if (ec) {
    throw InputError("cannot list demonstration folder '" + directory.string() +
                     "': " + ec.message());
  }
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    const fs::path& path = it->path();
    const std::string name = path.filename().string();
    // a *.csv that is not a regular file (a folder, a FIFO, a device) is read too, and so
    // rejected by name (ReadInputFile) instead of skipped without a word.
    if (name.empty() || name.front() == '.' || path.extension() != ".csv") continue;
    files.push_back(path);
  }
  if (ec) {
    throw InputError("cannot list demonstration folder '" + directory.string() +
                     "': " + ec.message());
  }
  std::sort(files.begin(), files.end(),
            [](const fs::path& a, const fs::path& b) { return a.filename() < b.filename(); });

  DemoDirectory result;
  result.directory = name.empty() ? directory.string() : name;
  for (const fs::path& path : files) {
    // as the folder is named: `directory` / file name is what the listing gives.
    const std::string source =
        name.empty() ? path.string() : (fs::path(name) / path.filename()).string();
    try {
      result.logs.push_back(ParseDemoLog(ReadInputFile(path, input_kind::kDemoLog), source));
    } catch (const InputError& e) {
      result.rejected.push_back({source, e.what()});
    }
  }
  return result;
}

DemoDirectory ReadDefaultDemoDirectory(const std::string& object_name) {
  const fs::path directory = DefaultDemoDirectory(object_name);
  return ReadDemoDirectory(directory, DataRelativeName(directory));
}

std::filesystem::path ObjectLearningDataDirectory(const std::string& object_name) {
  const std::filesystem::path root = DataDirectory() / "learning_data";
  return object_name == "pan" ? root : root / "objects" / object_name;
}

std::filesystem::path DefaultDemoDirectory(const std::string& object_name) {
  return ObjectLearningDataDirectory(object_name) / "demos";
}

}  // namespace graspsynth
