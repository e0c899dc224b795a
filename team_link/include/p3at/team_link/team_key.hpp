#pragma once
/// The team key: 32 secret bytes shared by every robot of a team, used to
/// authenticate team-link messages (HMAC-SHA512-256, docs/team-link.md).
///
/// Key file format: the 32 bytes as 64 hexadecimal characters (either case) in
/// a text file; leading and trailing whitespace is ignored. Create one with
/// `p3at_team_key FILE` (mode 0600) and copy it to every robot of the team.

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "p3at/common/result.hpp"

namespace p3at::hal {

/// A copy of the secret; the destructor wipes it from memory.
class TeamKey {
 public:
  static constexpr std::size_t kBytes = 32;
  using Bytes = std::array<std::uint8_t, kBytes>;

  explicit TeamKey(const Bytes& bytes) : bytes_(bytes) {}
  TeamKey(const TeamKey&) = default;
  TeamKey& operator=(const TeamKey&) = default;
  ~TeamKey();

  const Bytes& bytes() const { return bytes_; }

 private:
  Bytes bytes_;
};

/// Parses key-file text. `source_name` (a file path) starts every error message.
/// Errors (Error::Code::invalid_argument): not exactly 64 characters after
/// trimming whitespace, or a character that is not hexadecimal.
Result<TeamKey> parse_team_key(std::string_view text, std::string_view source_name);

/// Reads and parses a key file. A missing or unreadable file is
/// Error::Code::not_found / refused, naming the file.
Result<TeamKey> load_team_key(const std::string& path);

/// A fresh key from the operating system's random source (libsodium).
Result<TeamKey> generate_team_key();

/// The key as 64 lower-case hexadecimal characters (the key-file format).
std::string team_key_hex(const TeamKey& key);

/// A short, non-secret name for a key (16 hex characters of a BLAKE2b hash of
/// it), so operators can check that robots hold the same key without showing it.
std::string team_key_fingerprint(const TeamKey& key);

/// Writes `key` as a key file with mode 0600. Refuses to replace an existing
/// file unless `overwrite` (then the file is truncated and its mode set to 0600).
Status write_team_key_file(const std::string& path, const TeamKey& key, bool overwrite);

}  // namespace p3at::hal
