#include "teleop/packet_key.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>
#include <sys/stat.h>

#include <cctype>
#include <stdexcept>

#include "common/atomic_file.hpp"
#include "common/errors.hpp"
#include "common/input_file.hpp"
#include "common/text_input.hpp"

namespace graspsynth::teleop {
namespace {

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string SizeProblem(size_t size) {
  if (size < kMinKeyBytes) {
    return "the key has " + std::to_string(size) + " bytes; at least " +
           std::to_string(kMinKeyBytes) +
           " are needed (graspsynth teleop-keygen --out FILE writes a 32-byte key)";
  }
  if (size > kMaxKeyBytes) {
    return "the key has " + std::to_string(size) + " bytes; at most " +
           std::to_string(kMaxKeyBytes) + " are taken";
  }
  return "";
}

}  // namespace

PacketKey::PacketKey(std::vector<uint8_t> bytes) : bytes_(std::move(bytes)) {
  const std::string problem = SizeProblem(bytes_.size());
  if (!problem.empty()) throw InputError("teleoperation key: " + problem);
}

PacketKey PacketKey::Load(const std::filesystem::path& path) {
  const std::string contents = ReadInputFile(path, input_kind::kKey);
  const std::string where = "key file " + path.string();
  std::vector<uint8_t> key;
  int key_line = 0;
  int number = 0;
  for (const std::string_view line : SplitFields(contents, '\n')) {
    ++number;
    const std::string_view text = TrimBlanks(line);
    if (text.empty() || text.front() == '#') continue;
    const std::string at = where + ": line " + std::to_string(number);
    if (key_line != 0) {
      throw InputError(at + ": a second key line (the key is on line " + std::to_string(key_line) +
                       "; one key per file)");
    }
    key_line = number;
    for (size_t i = 0; i < text.size(); ++i) {
      if (HexDigit(text[i]) < 0) {
        throw InputError(at + ": character " + std::to_string(i + 1) +
                         " is not a hexadecimal digit (the key is written in hex, 0-9 a-f)");
      }
    }
    if (text.size() % 2 != 0) {
      throw InputError(at + ": an odd number of hexadecimal digits (" +
                       std::to_string(text.size()) + "); each byte takes two");
    }
    for (size_t i = 0; i < text.size(); i += 2) {
      key.push_back(static_cast<uint8_t>(HexDigit(text[i]) * 16 + HexDigit(text[i + 1])));
    }
    const std::string problem = SizeProblem(key.size());
    if (!problem.empty()) throw InputError(at + ": " + problem);
  }
  if (key_line == 0) {
    throw InputError(where +
                     ": no key line (only blank lines and comments); "
                     "graspsynth teleop-keygen --out FILE writes a key");
  }
  if (const std::optional<std::string> shared = KeyFileSharedWith(path)) {
    throw InputError(where + ": can be read by " + *shared +
                     ", so the key is not secret; chmod 600 it (as ssh does, a key that others "
                     "can read is refused)");
  }
  return PacketKey(std::move(key));
}

PacketKey PacketKey::Generate() {
  std::vector<uint8_t> bytes(32);
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) {
    throw std::runtime_error("OpenSSL's random generator failed to make a key");
  }
  return PacketKey(std::move(bytes));
}

std::string PacketKey::FileText() const {
  static const char kHex[] = "0123456789abcdef";
  std::string text =
      "# graspsynth teleoperation key (HMAC-SHA256); keep it secret, give it to the client and "
      "the server only\n";
  for (uint8_t b : bytes_) {
    text += kHex[b >> 4];
    text += kHex[b & 0xF];
  }
  return text + "\n";
}

std::array<uint8_t, kTagBytes> PacketKey::Tag(std::span<const uint8_t> bytes) const {
  std::array<uint8_t, kTagBytes> tag{};
  unsigned int length = 0;
  const unsigned char* done = HMAC(EVP_sha256(), bytes_.data(), static_cast<int>(bytes_.size()),
                                   bytes.data(), bytes.size(), tag.data(), &length);
  if (done == nullptr || length != kTagBytes) {
    throw std::runtime_error("OpenSSL's HMAC-SHA256 failed");
  }
  return tag;
}

bool PacketKey::Verifies(std::span<const uint8_t> bytes, std::span<const uint8_t> tag) const {
  if (tag.size() != kTagBytes) return false;
  std::array<uint8_t, kTagBytes> expected;
  try {
    expected = Tag(bytes);
  } catch (const std::exception&) {
    return false;  // never thrown in practice; a packet that cannot be checked is refused
  }
  return CRYPTO_memcmp(expected.data(), tag.data(), kTagBytes) == 0;
}

std::optional<std::string> KeyFileSharedWith(const std::filesystem::path& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return std::nullopt;
  const bool group = (st.st_mode & S_IRGRP) != 0, others = (st.st_mode & S_IROTH) != 0;
  if (group && others) return "its group and other users";
  if (group) return "its group";
  if (others) return "other users";
  return std::nullopt;
}

void WriteNewPacketKey(const std::filesystem::path& path) {
  CreateOwnerOnlyFileAtomically(path, PacketKey::Generate().FileText());
}

}  // namespace graspsynth::teleop
