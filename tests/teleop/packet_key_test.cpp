// The teleoperation link's key files: reading (every defect named by file and line, the key
// never shown), writing a new one (owner-only, never over an existing file).

#include "teleop/packet_key.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/errors.hpp"
#include "tests/utils/eigen_matchers.hpp"
#include "tests/utils/test_folder.hpp"

namespace graspsynth::teleop {
namespace {

namespace fs = std::filesystem;

class KeyFile : public ::testing::Test {
 protected:
  fs::path Write(const std::string& text) {
    const fs::path path = dir_ / "link.key";
    std::ofstream(path) << text;
    fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);
    return path;
  }
  graspsynth::testing::TestFolder folder_;
  const fs::path& dir_ = folder_.path();
};

constexpr const char* kKeyHex = "00112233445566778899AaBbCcDdEeFf";  // 16 bytes

TEST_F(KeyFile, ReadsTheHexLineBetweenCommentsAndBlankLines) {
  const PacketKey key = PacketKey::Load(Write(std::string("# a comment\n\n  ") + kKeyHex + "  \n"));
  std::vector<uint8_t> bytes;
  for (int i = 0; i < 16; ++i) bytes.push_back(static_cast<uint8_t>(0x11 * i));
  const PacketKey same(bytes);
  const std::vector<uint8_t> text = {1, 2, 3};
  EXPECT_EQ(key.Tag(text), same.Tag(text));
  EXPECT_TRUE(key.Verifies(text, same.Tag(text)));
  const std::vector<uint8_t> changed = {1, 2, 4};
  EXPECT_FALSE(key.Verifies(changed, same.Tag(text)));
  // its file text reads back as the same key.
  const PacketKey back = PacketKey::Load(Write(key.FileText()));
  EXPECT_EQ(back.Tag(text), key.Tag(text));
}

TEST_F(KeyFile, EachDefectIsNamedWithTheFileAndLineButNotTheKey) {
  const std::string file = (dir_ / "link.key").string();
  GS_EXPECT_THROW_WITH(PacketKey::Load(Write("# key\n0011zz33445566778899aabbccddeeff\n")),
                       InputError, file, "line 2", "character 5 is not a hexadecimal digit");
  GS_EXPECT_THROW_WITH(PacketKey::Load(Write(std::string(kKeyHex) + "0\n")), InputError, file,
                       "line 1", "odd number");
  GS_EXPECT_THROW_WITH(PacketKey::Load(Write("0011223344\n")), InputError, file, "line 1",
                       "5 bytes; at least 16", "teleop-keygen");
  GS_EXPECT_THROW_WITH(PacketKey::Load(Write(std::string(kKeyHex) + "\n" + kKeyHex + "\n")),
                       InputError, file, "line 2", "a second key line");
  GS_EXPECT_THROW_WITH(PacketKey::Load(Write("# only a comment\n\n")), InputError, file,
                       "no key line");
  GS_EXPECT_THROW_WITH(PacketKey::Load(dir_ / "none.key"), InputError, "none.key", "cannot read");
  try {
    PacketKey::Load(Write(std::string(kKeyHex) + "0\n"));
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("8899"), std::string::npos) << e.what();
  }
  GS_EXPECT_THROW_WITH(PacketKey(std::vector<uint8_t>(15, 1)), InputError, "15 bytes");
}

TEST_F(KeyFile, ANewKeyIsOwnerOnlyRandomAndNeverOverwritten) {
  const fs::path a = dir_ / "a.key", b = dir_ / "b.key";
  WriteNewPacketKey(a);
  WriteNewPacketKey(b);
  struct stat st {};
  ASSERT_EQ(::stat(a.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  EXPECT_FALSE(KeyFileSharedWith(a));
  const std::vector<uint8_t> text = {7};
  EXPECT_NE(PacketKey::Load(a).Tag(text), PacketKey::Load(b).Tag(text));  // two random keys
  const std::string before = [&] {
    std::ifstream in(a);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }();
  GS_EXPECT_THROW_WITH(WriteNewPacketKey(a), InputError, a.string(), "never overwritten");
  std::ifstream in(a);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), before);
  // no temporary file is left behind.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()), 2);
}

TEST_F(KeyFile, AKeyThatOthersCanReadIsRefusedAsSshRefusesIt) {
  const fs::path key = Write(std::string(kKeyHex) + "\n");
  EXPECT_FALSE(KeyFileSharedWith(key));
  fs::permissions(key, fs::perms::group_read, fs::perm_options::add);
  EXPECT_EQ(KeyFileSharedWith(key), "its group");
  GS_EXPECT_THROW_WITH(PacketKey::Load(key), InputError, key.string(), "can be read by its group",
                       "chmod 600");
  fs::permissions(key, fs::perms::others_read, fs::perm_options::add);
  GS_EXPECT_THROW_WITH(PacketKey::Load(key), InputError, "its group and other users");
  fs::permissions(key, fs::perms::group_read, fs::perm_options::remove);
  GS_EXPECT_THROW_WITH(PacketKey::Load(key), InputError, "can be read by other users");
}

TEST_F(KeyFile, AnEndlessStreamAFifoOrAFolderIsRefusedByName) {
  GS_EXPECT_THROW_WITH(PacketKey::Load("/dev/zero"), InputError, "/dev/zero",
                       "a character device, not a regular file");
  const fs::path fifo = dir_ / "fifo.key";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  GS_EXPECT_THROW_WITH(PacketKey::Load(fifo), InputError, fifo.string(), "named pipe (FIFO)");
  GS_EXPECT_THROW_WITH(PacketKey::Load(dir_), InputError, "a folder, not a regular file");
  // a key file has at most 64 KiB (one key line of at most 2048 digits and comments).
  const fs::path big = Write("# " + std::string(70000, 'x') + "\n" + kKeyHex + "\n");
  GS_EXPECT_THROW_WITH(PacketKey::Load(big), InputError, "over the limit of 65536 bytes");
}

}  // namespace
}  // namespace graspsynth::teleop
