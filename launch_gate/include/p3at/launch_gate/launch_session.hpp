#pragma once
/// The launch session (docs/launch-gate.md, "The launch as an agreement"):
/// every gate draws a fresh random nonce; the session id binds the mission's
/// content hash to the nonces of every robot of this run, so a message of any
/// other run (a recording played back, a robot's earlier process) names
/// another session and is rejected.

#include <string>
#include <vector>

#include "p3at/hal/team_link.hpp"

namespace p3at::gate {

/// 16 bytes from libsodium's randombytes, as 32 lowercase hex digits.
std::string fresh_gate_nonce();

/// BLAKE2b-256 (libsodium crypto_generichash) as 64 lowercase hex digits, over
/// the domain string "p3at-launch-session-v1" and a NUL, the mission hash and a
/// newline, then one line "robot:nonce\n" per robot, sorted by robot name.
/// Independent of the order of `nonces`.
std::string launch_session_id(const std::string& mission_hash, std::vector<hal::HeardNonce> nonces);

}  // namespace p3at::gate
