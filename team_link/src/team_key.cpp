#include "p3at/team_link/team_key.hpp"

#include <fcntl.h>
#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace p3at::hal {

namespace {

// A key file is 64 characters plus whitespace; anything much larger is not one,
// and reading it whole would only waste memory.
constexpr std::size_t kMaxKeyFileBytes = 4096;

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

Error errno_error(const std::string& path, const char* what, int err) {
  const Error::Code code = err == ENOENT ? Error::Code::not_found
                           : (err == EACCES || err == EPERM || err == EEXIST) ? Error::Code::refused
                                                                              : Error::Code::io;
  return make_error(code, "team key file '" + path + "': " + what + ": " + std::strerror(err));
}

}  // namespace

TeamKey::~TeamKey() { sodium_memzero(bytes_.data(), bytes_.size()); }

Result<TeamKey> parse_team_key(std::string_view text, std::string_view source_name) {
  const std::string prefix = "team key file '" + std::string(source_name) + "': ";
  while (!text.empty() && is_space(text.front())) text.remove_prefix(1);
  while (!text.empty() && is_space(text.back())) text.remove_suffix(1);
  if (text.size() != 2 * TeamKey::kBytes) {
    return make_error(Error::Code::invalid_argument,
                      prefix + "expected 64 hexadecimal characters (32 bytes), found " +
                          std::to_string(text.size()) + " characters (create one with `p3at_team_key FILE`)");
  }
  TeamKey::Bytes bytes{};
  for (std::size_t i = 0; i < text.size(); ++i) {
    const int v = hex_value(text[i]);
    if (v < 0) {
      sodium_memzero(bytes.data(), bytes.size());
      return make_error(Error::Code::invalid_argument,
                        prefix + "character " + std::to_string(i + 1) + " is not hexadecimal");
    }
    auto& b = bytes[i / 2];
    b = static_cast<std::uint8_t>((b << 4) | v);
  }
  if (sodium_is_zero(bytes.data(), bytes.size()) != 0) {
    return make_error(Error::Code::invalid_argument,
                      prefix + "the key is all zeros, not a secret (create one with `p3at_team_key FILE`)");
  }
  TeamKey key(bytes);
  sodium_memzero(bytes.data(), bytes.size());
  return key;
}

Result<TeamKey> load_team_key(const std::string& path) {
  // O_NONBLOCK: opening a FIFO must not wait for a writer; the checks below
  // refuse anything but a regular file before a byte is read.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) return errno_error(path, "cannot open", errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return errno_error(path, "cannot stat", err);
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    const char* kind = S_ISDIR(st.st_mode) ? "a directory" : S_ISFIFO(st.st_mode) ? "a FIFO" : S_ISSOCK(st.st_mode) ? "a socket"
                       : (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) ? "a device" : "not a regular file";
    return make_error(Error::Code::invalid_argument, "team key file '" + path + "': is " + std::string(kind) +
                                                         ", not a regular file");
  }
  if ((st.st_mode & 0077) != 0) {
    // As ssh insists for private keys: a key others can read is no secret.
    ::close(fd);
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", st.st_mode & 07777u);
    return make_error(Error::Code::refused, "team key file '" + path + "': mode " + mode +
                                                " lets others read or write it; it must be readable by its owner "
                                                "only (chmod 600 '" + path + "')");
  }
  std::string text(kMaxKeyFileBytes + 1, '\0');
  std::size_t used = 0;
  while (used < text.size()) {
    const ssize_t n = ::read(fd, text.data() + used, text.size() - used);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      ::close(fd);
      return errno_error(path, "cannot read", err);
    }
    if (n == 0) break;
    used += static_cast<std::size_t>(n);
  }
  ::close(fd);
  if (used > kMaxKeyFileBytes) {
    sodium_memzero(text.data(), text.size());
    return make_error(Error::Code::invalid_argument,
                      "team key file '" + path + "': larger than " + std::to_string(kMaxKeyFileBytes) +
                          " bytes, not a key file");
  }
  auto key = parse_team_key(std::string_view(text.data(), used), path);
  sodium_memzero(text.data(), text.size());
  return key;
}

Result<TeamKey> generate_team_key() {
  if (sodium_init() < 0) return make_error(Error::Code::io, "libsodium failed to initialise");
  TeamKey::Bytes bytes{};
  randombytes_buf(bytes.data(), bytes.size());
  TeamKey key(bytes);
  sodium_memzero(bytes.data(), bytes.size());
  return key;
}

std::string team_key_hex(const TeamKey& key) {
  std::string hex(2 * TeamKey::kBytes + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), key.bytes().data(), key.bytes().size());
  hex.pop_back();  // sodium_bin2hex writes a terminating NUL
  return hex;
}

std::string team_key_fingerprint(const TeamKey& key) {
  std::array<unsigned char, 8> hash{};
  // Domain-separated so the fingerprint is never equal to any MAC we send.
  static constexpr unsigned char kContext[] = "p3at team key fingerprint";
  crypto_generichash(hash.data(), hash.size(), key.bytes().data(), key.bytes().size(), kContext,
                     sizeof kContext - 1);
  std::string hex(2 * hash.size() + 1, '\0');
  sodium_bin2hex(hex.data(), hex.size(), hash.data(), hash.size());
  hex.pop_back();
  return hex;
}

Status write_team_key_file(const std::string& path, const TeamKey& key, bool overwrite) {
  // O_NONBLOCK and O_NOFOLLOW: --force on a FIFO must not wait for a reader,
  // and a key is never written through a symbolic link; anything but a
  // regular file is refused below before a byte is written.
  const int flags = O_WRONLY | O_CREAT | O_CLOEXEC | O_NONBLOCK | O_NOFOLLOW | (overwrite ? O_TRUNC : O_EXCL);
  const int fd = ::open(path.c_str(), flags, 0600);
  if (fd < 0 && errno == ENXIO) {  // a FIFO with no reader
    return make_error(Error::Code::invalid_argument, "team key file '" + path + "': is a FIFO, not a regular file");
  }
  if (fd < 0) {
    if (errno == EEXIST) {
      return make_error(Error::Code::refused,
                        "team key file '" + path + "': already exists (refusing to replace a team key)");
    }
    return errno_error(path, "cannot create", errno);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd);
    return make_error(Error::Code::invalid_argument, "team key file '" + path + "': not a regular file");
  }
  // O_CREAT's mode does not apply to an existing file, and the umask may differ.
  if (::fchmod(fd, 0600) != 0) {
    const int err = errno;
    ::close(fd);
    return errno_error(path, "cannot set mode 0600", err);
  }
  std::string text = team_key_hex(key) + "\n";
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int err = errno;
      sodium_memzero(text.data(), text.size());
      ::close(fd);
      return errno_error(path, "cannot write", err);
    }
    done += static_cast<std::size_t>(n);
  }
  sodium_memzero(text.data(), text.size());
  const int sync_rc = ::fsync(fd);
  const int sync_errno = errno;
  if (::close(fd) != 0) return errno_error(path, "cannot write", errno);
  if (sync_rc != 0) return errno_error(path, "cannot write", sync_errno);
  return {};
}

}  // namespace p3at::hal
