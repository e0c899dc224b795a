#include "p3at/launch_gate/launch_session.hpp"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string_view>

namespace p3at::gate {
namespace {

constexpr std::string_view kDomain{"p3at-launch-session-v1\0", 23};

std::string to_hex(const unsigned char* bytes, std::size_t size) {
  std::string text(2 * size + 1, '\0');
  sodium_bin2hex(text.data(), text.size(), bytes, size);
  text.resize(2 * size);
  return text;
}

void ensure_sodium() {
  // sodium_init() is idempotent and thread-safe; without it randombytes may
  // not be seeded, and a predictable nonce would make sessions replayable.
  if (sodium_init() < 0) throw std::runtime_error("libsodium failed to initialise");
}

}  // namespace

std::string fresh_gate_nonce() {
  ensure_sodium();
  std::array<unsigned char, 16> nonce{};
  randombytes_buf(nonce.data(), nonce.size());
  return to_hex(nonce.data(), nonce.size());
}

std::string launch_session_id(const std::string& mission_hash, std::vector<hal::HeardNonce> nonces) {
  ensure_sodium();
  std::sort(nonces.begin(), nonces.end(),
            [](const hal::HeardNonce& a, const hal::HeardNonce& b) { return a.robot < b.robot; });
  std::string text(kDomain);
  text += mission_hash;
  text += '\n';
  for (const hal::HeardNonce& n : nonces) text += n.robot + ":" + n.nonce + "\n";
  std::array<unsigned char, 32> digest{};
  crypto_generichash(digest.data(), digest.size(), reinterpret_cast<const unsigned char*>(text.data()), text.size(),
                     nullptr, 0);
  return to_hex(digest.data(), digest.size());
}

}  // namespace p3at::gate
