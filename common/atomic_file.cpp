#include "common/atomic_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "common/errors.hpp"

namespace graspsynth {

namespace fs = std::filesystem;

void WriteFileAtomically(const fs::path& path, std::string_view contents) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    throw InputError("cannot create folder '" + parent.string() + "': " + ec.message());
  }
  // the temporary name is unique per process, so concurrent writers never share it.
  std::string tmp_name(1, '.');
  tmp_name += path.filename().string();
  tmp_name += ".tmp.";
  tmp_name += std::to_string(::getpid());
  const fs::path tmp = parent / tmp_name;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) {
      throw InputError("cannot write '" + tmp.string() + "': " + std::strerror(errno));
    }
    out.write(contents.data(), static_cast<std::streamsize>(contents.size()));
    out.flush();
    if (!out) {
      fs::remove(tmp, ec);
      throw InputError("error while writing '" + tmp.string() + "'");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp, ec);
    throw InputError("cannot rename '" + tmp.string() + "' to '" + path.string() +
                     "': " + ec.message());
  }
}

}  // namespace graspsynth
