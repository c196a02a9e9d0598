// Tests of common/input_file.hpp: every byte of a regular file comes back; a missing file, a
// folder, a named pipe, a device and a socket are refused by name without blocking or reading;
// a file over its kind's limit is refused; a path with a NUL byte is refused, not cut.

#include "common/input_file.hpp"

#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <future>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth {
namespace {

namespace fs = std::filesystem;

constexpr InputFileKind kTiny{"tiny file", 10};

class InputFileTest : public ::testing::Test {
 protected:
  fs::path Write(const std::string& name, const std::string& bytes) {
    std::ofstream(dir_ / name, std::ios::binary) << bytes;
    return dir_ / name;
  }
  graspsynth::testing::TestFolder folder_;
  const fs::path& dir_ = folder_.path();
};

TEST_F(InputFileTest, ReturnsEveryByteOfARegularFile) {
  const std::string bytes("line 1\r\nnul \0 inside\n\xff", 22);
  EXPECT_EQ(ReadInputFile(Write("bytes.bin", bytes), input_kind::kJson), bytes);
  EXPECT_EQ(ReadInputFile(Write("empty.txt", ""), input_kind::kJson), "");
  // exactly at the limit is taken.
  EXPECT_EQ(ReadInputFile(Write("ten.txt", "0123456789"), kTiny), "0123456789");
  // through a link, the file it names.
  fs::create_symlink(dir_ / "ten.txt", dir_ / "link.txt");
  EXPECT_EQ(ReadInputFile(dir_ / "link.txt", kTiny), "0123456789");
}

TEST_F(InputFileTest, AMissingFileOrAFolderIsRefusedByName) {
  GS_EXPECT_THROW_WITH(ReadInputFile(dir_ / "none.json", input_kind::kObject), InputError,
                       "cannot read object description '" + (dir_ / "none.json").string() + "'",
                       "no such file");
  GS_EXPECT_THROW_WITH(ReadInputFile(dir_, input_kind::kScene), InputError,
                       "cannot read scene description '" + dir_.string() + "'",
                       "it is a folder, not a regular file");
  GS_EXPECT_THROW_WITH(ReadInputFile(Write("f", "x") / "below", input_kind::kJson), InputError,
                       "a folder on its path is a file");
  GS_EXPECT_THROW_WITH(ReadInputFile("", input_kind::kJson), InputError, "the path is empty");
}

TEST_F(InputFileTest, DevicesAreRefusedWithoutReadingAByte) {
  // each of them would give bytes for ever (or block): refused before they are opened.
  GS_EXPECT_THROW_WITH(
      ReadInputFile("/dev/zero", input_kind::kMesh), InputError,
      "cannot read mesh '/dev/zero': it is a character device, not a regular file");
  GS_EXPECT_THROW_WITH(ReadInputFile("/dev/urandom", input_kind::kKey), InputError,
                       "a character device");
  // a link to a device is the device.
  fs::create_symlink("/dev/zero", dir_ / "zero.stl");
  GS_EXPECT_THROW_WITH(ReadInputFile(dir_ / "zero.stl", input_kind::kMesh), InputError,
                       (dir_ / "zero.stl").string(), "a character device");
}

TEST_F(InputFileTest, ANamedPipeIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "object.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // opening a FIFO for reading waits for a writer: the read runs on another thread, and should
  // it block (a regression), a writer comes after a minute to free it, and the test fails.
  auto read = std::async(std::launch::async, [&] {
    try {
      ReadInputFile(fifo, input_kind::kObject);
      return std::string("read");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
  });
  if (read.wait_for(std::chrono::seconds(60)) != std::future_status::ready) {
    ADD_FAILURE() << "reading a FIFO blocked";
    const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
    if (writer >= 0) ::close(writer);
  }
  EXPECT_THAT(read.get(), ::testing::HasSubstr("it is a named pipe (FIFO), not a regular file"));
}

TEST_F(InputFileTest, ASocketIsRefused) {
  const fs::path path = dir_ / "s.sock";
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  ASSERT_LT(path.string().size(), sizeof address.sun_path);
  std::strcpy(address.sun_path, path.c_str());
  ASSERT_EQ(::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
  GS_EXPECT_THROW_WITH(ReadInputFile(path, input_kind::kJson), InputError, "a socket");
  ::close(fd);
}

TEST_F(InputFileTest, AFileOverItsKindsLimitIsRefusedNamingTheLimit) {
  GS_EXPECT_THROW_WITH(ReadInputFile(Write("eleven.txt", "0123456789A"), kTiny), InputError,
                       "cannot read tiny file", "it holds 11 bytes, over the limit of 10 bytes",
                       "Input limits");
  // a sparse file of 300 MiB: refused from its size, nothing allocated for it.
  const fs::path big = dir_ / "big.json";
  { std::ofstream(big) << "{}"; }
  fs::resize_file(big, 300 * input_kind::kMiB);
  GS_EXPECT_THROW_WITH(ReadInputFile(big, input_kind::kLibrary), InputError,
                       "cannot read grasp library", "over the limit of 268435456 bytes");
}

TEST_F(InputFileTest, APathWithANulByteIsRefusedNotCut) {
  Write("a.json", "{}");
  const fs::path cut(std::string((dir_ / "a.json").string() + std::string("\0.stl", 5)));
  GS_EXPECT_THROW_WITH(ReadInputFile(cut, input_kind::kMesh), InputError,
                       "the path holds a NUL byte", "a.json\\0.stl");
}

}  // namespace
}  // namespace graspsynth
