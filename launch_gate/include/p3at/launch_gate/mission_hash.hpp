#pragma once
/// The mission's content hash: what the robots of a team must agree on before
/// launching (docs/launch-gate.md). Two robots with the same hash verified the
/// same mission against the same robot models.

#include <string>
#include <string_view>
#include <vector>

#include "p3at/common/file_bytes.hpp"
#include "p3at/common/result.hpp"
#include "p3at/verifier/models.hpp"

namespace p3at::gate {

/// BLAKE2b-256 (libsodium's crypto_generichash) as 64 lowercase hex digits,
/// over, in order: the domain string "p3at-launch-gate-v1" and a NUL; the
/// mission file's bytes; the models file's bytes; the walls of the loaded
/// models (which may come from another file, `environment.walls_from`), each
/// coordinate as its IEEE-754 bits. Every part is preceded by its length as 8
/// big-endian bytes, so no two different inputs give the same byte stream.
/// Raw bytes, not a canonical print: a comment or a reformatted line changes
/// the hash, so robots must be given byte-identical files (copy them).
std::string mission_content_hash(std::string_view mission_bytes, std::string_view models_bytes,
                                 const std::vector<verifier::Wall>& walls);

/// Reads a whole file (common/file_bytes.hpp). Error (not_found / io) names the file.
using ::p3at::read_file_bytes;

}  // namespace p3at::gate
