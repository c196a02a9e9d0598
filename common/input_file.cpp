#include "common/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "common/errors.hpp"

namespace graspsynth {

namespace {

// What a file that is not a regular one is, in words.
std::string NotRegular(mode_t mode) {
  std::string what = "something other than a regular file";
  if (S_ISDIR(mode)) what = "a folder";
  if (S_ISFIFO(mode)) what = "a named pipe (FIFO)";
  if (S_ISCHR(mode)) what = "a character device";
  if (S_ISBLK(mode)) what = "a block device";
  if (S_ISSOCK(mode)) what = "a socket";
  return "it is " + what + ", not a regular file";
}

std::string SystemReason(int error) {
  if (error == ENOENT) return "no such file";
  if (error == ENOTDIR) return "a folder on its path is a file";
  return std::strerror(error);
}

std::string OverLimit(uint64_t bytes, const InputFileKind& kind, bool at_least) {
  return "it holds " + std::string(at_least ? "more than " : "") + std::to_string(bytes) +
         " bytes, over the limit of " + std::to_string(kind.max_bytes) + " bytes for a " +
         std::string(kind.name) + " (docs/formats.md, \"Input limits\")";
}

// `path` as messages show it: its text, with a NUL byte written as "\0".
std::string ShownPath(const std::filesystem::path& path) {
  std::string shown;
  for (const char c : path.native()) {
    if (c == '\0') {
      shown += "\\0";
    } else {
      shown += c;
    }
  }
  return shown;
}

// Closes a file descriptor when it goes out of scope.
class FileDescriptor {
 public:
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

std::string ReadInputFile(const std::filesystem::path& path, const InputFileKind& kind) {
  const std::string& native = path.native();
  const auto refuse = [&](const std::string& why) -> InputError {
    return InputError("cannot read " + std::string(kind.name) + " '" + ShownPath(path) +
                      "': " + why);
  };
  if (native.find('\0') != std::string::npos) throw refuse("the path holds a NUL byte");
  if (native.empty()) throw refuse("the path is empty");
  // a regular file within the limit, or the refusal.
  const auto require_regular = [&](const struct stat& st) {
    if (!S_ISREG(st.st_mode)) throw refuse(NotRegular(st.st_mode));
    if (static_cast<uint64_t>(st.st_size) > kind.max_bytes) {
      throw refuse(OverLimit(static_cast<uint64_t>(st.st_size), kind, false));
    }
  };
  // look before opening: opening a FIFO for reading blocks until a writer comes, and a device
  // may never end.
  struct stat st {};
  if (::stat(native.c_str(), &st) != 0) throw refuse(SystemReason(errno));
  require_regular(st);
  // O_NONBLOCK: whatever was put at the path since the look, opening it does not block; the
  // look is repeated on what was opened.
  const FileDescriptor fd(::open(native.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw refuse(SystemReason(errno));
  if (::fstat(fd.get(), &st) != 0) throw refuse(SystemReason(errno));
  require_regular(st);
  std::string bytes;
  bytes.resize(static_cast<size_t>(st.st_size));
  size_t filled = 0;
  // read until the end: the file may have grown since fstat, up to the limit and one byte more.
  while (true) {
    if (filled == bytes.size()) {
      if (bytes.size() > kind.max_bytes) throw refuse(OverLimit(kind.max_bytes, kind, true));
      const size_t grown = std::max<size_t>(bytes.size() * 2, 4096);
      bytes.resize(std::min<size_t>(grown, kind.max_bytes + 1));
    }
    const ssize_t n = ::read(fd.get(), bytes.data() + filled, bytes.size() - filled);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw refuse("reading failed: " + SystemReason(errno));
    }
    if (n == 0) break;
    filled += static_cast<size_t>(n);
  }
  bytes.resize(filled);
  return bytes;
}

}  // namespace graspsynth
