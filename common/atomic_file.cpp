#include "common/atomic_file.hpp"

#include <fcntl.h>
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

namespace {

// The folder of `path`, created when missing, and a temporary name in it that is unique per
// process, so that concurrent writers never share it.
fs::path TemporaryBeside(const fs::path& path) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) {
    throw InputError("cannot create folder '" + parent.string() + "': " + ec.message());
  }
  std::string tmp_name(1, '.');
  tmp_name += path.filename().string();
  tmp_name += ".tmp.";
  tmp_name += std::to_string(::getpid());
  return parent / tmp_name;
}

}  // namespace

void WriteFileAtomically(const fs::path& path, std::string_view contents) {
  const fs::path tmp = TemporaryBeside(path);
  std::error_code ec;
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

void CreateOwnerOnlyFileAtomically(const fs::path& path, std::string_view contents) {
  const fs::path tmp = TemporaryBeside(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw InputError("cannot write '" + tmp.string() + "': " + std::strerror(errno));
  }
  const bool written =
      ::write(fd, contents.data(), contents.size()) == static_cast<ssize_t>(contents.size());
  const bool closed = ::close(fd) == 0;
  // link() refuses an existing destination: an existing file is never replaced.
  const bool linked = written && closed && ::link(tmp.c_str(), path.c_str()) == 0;
  const int link_errno = errno;
  ::unlink(tmp.c_str());
  if (!written || !closed) throw InputError("error while writing '" + tmp.string() + "'");
  if (!linked) {
    throw InputError(link_errno == EEXIST
                         ? "'" + path.string() + "' exists; it is never overwritten"
                         : "cannot write '" + path.string() + "': " + std::strerror(link_errno));
  }
}

}  // namespace graspsynth
