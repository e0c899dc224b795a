#include "p3at/launch_gate/mission_hash.hpp"

#include <sodium.h>

#include <array>
#include <bit>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace p3at::gate {
namespace {

constexpr std::string_view kDomain{"p3at-launch-gate-v1\0", 20};

class Hasher {
 public:
  Hasher() { crypto_generichash_init(&state_, nullptr, 0, kDigestBytes); }

  void part(std::string_view bytes) {
    length(bytes.size());
    raw(bytes.data(), bytes.size());
  }

  void number(double value) { big_endian(std::bit_cast<std::uint64_t>(value)); }
  void length(std::uint64_t size) { big_endian(size); }

  std::string hex() {
    std::array<unsigned char, kDigestBytes> digest{};
    crypto_generichash_final(&state_, digest.data(), digest.size());
    std::array<char, 2 * kDigestBytes + 1> text{};
    sodium_bin2hex(text.data(), text.size(), digest.data(), digest.size());
    return std::string(text.data(), 2 * kDigestBytes);
  }

 private:
  static constexpr std::size_t kDigestBytes = 32;

  void big_endian(std::uint64_t n) {
    std::array<unsigned char, 8> be{};
    for (std::size_t i = 0; i < be.size(); ++i) be[i] = static_cast<unsigned char>(n >> (56 - 8 * i));
    raw(be.data(), be.size());
  }

  void raw(const void* data, std::size_t size) {
    crypto_generichash_update(&state_, static_cast<const unsigned char*>(data), size);
  }

  crypto_generichash_state state_{};
};

}  // namespace

std::string mission_content_hash(std::string_view mission_bytes, std::string_view models_bytes,
                                 const std::vector<verifier::Wall>& walls) {
  // sodium_init() is idempotent and thread-safe; generichash needs no more than this.
  if (sodium_init() < 0) return std::string(64, '0');
  Hasher h;
  h.part(kDomain);
  h.part(mission_bytes);
  h.part(models_bytes);
  h.length(walls.size());
  for (const verifier::Wall& w : walls) {
    h.number(w.x0_m);
    h.number(w.y0_m);
    h.number(w.x1_m);
    h.number(w.y1_m);
  }
  return h.hex();
}


}  // namespace p3at::gate
