#pragma once

/// @file
/// The teleoperation link's shared key: every datagram can carry an HMAC-SHA256 tag computed
/// with a key that the operator's client and the robot's server both hold (teleop/protocol.hpp,
/// version 2 packets). The hash is OpenSSL's (libcrypto), the comparison constant-time.
///
/// Key file: UTF-8 text; blank lines and lines starting with '#' are ignored; exactly one line
/// holds the key as hexadecimal digits (upper or lower case), at least 32 digits (16 bytes);
/// `graspsynth teleop-keygen` writes one with 32 random bytes, readable only by its owner.
/// Errors name the file and the line and say what is wrong, never the key itself.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace graspsynth::teleop {

inline constexpr size_t kTagBytes = 32;     ///< HMAC-SHA256
inline constexpr size_t kMinKeyBytes = 16;  ///< shorter keys are refused
inline constexpr size_t kMaxKeyBytes = 1024;

/// A shared key.
class PacketKey {
 public:
  /// Throws InputError when `bytes` has fewer than kMinKeyBytes or more than kMaxKeyBytes.
  explicit PacketKey(std::vector<uint8_t> bytes);

  /// Reads a key file (format above). Throws InputError naming the file (and the line) for a
  /// missing or unreadable file (or one that is not a regular file, or over 64 KiB), a line
  /// that is not hexadecimal, an odd number of digits, no key line or more than one, a key too
  /// short or too long, and a file that its group or other users can read (KeyFileSharedWith),
  /// as ssh refuses such a private key.
  static PacketKey Load(const std::filesystem::path& path);

  /// A key of 32 bytes from OpenSSL's random generator. Throws std::runtime_error when the
  /// generator fails.
  static PacketKey Generate();

  /// The text of a key file holding this key (a comment line, then the hex digits).
  std::string FileText() const;

  /// HMAC-SHA256 of `bytes` with this key.
  std::array<uint8_t, kTagBytes> Tag(std::span<const uint8_t> bytes) const;

  /// True when `tag` is Tag(bytes); the comparison takes the same time wherever they differ.
  /// Never throws (false when the hash cannot be computed).
  bool Verifies(std::span<const uint8_t> bytes, std::span<const uint8_t> tag) const;

 private:
  std::vector<uint8_t> bytes_;
};

/// Who besides its owner can read the key file at `path` ("its group", "other users", or both),
/// or std::nullopt when nobody can (or the file cannot be looked at).
std::optional<std::string> KeyFileSharedWith(const std::filesystem::path& path);

/// Writes a new key (PacketKey::Generate) to `path`, readable and writable by its owner only
/// (mode 0600), never overwriting: the file appears whole or not at all. Throws InputError when
/// `path` exists or cannot be written.
void WriteNewPacketKey(const std::filesystem::path& path);

}  // namespace graspsynth::teleop
