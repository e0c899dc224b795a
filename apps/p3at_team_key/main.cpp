// p3at_team_key: the team key that authenticates team-link messages.
//   p3at_team_key team.key            write a fresh key (mode 0600); refuses to replace one
//   p3at_team_key --force team.key    replace an existing key file
//   p3at_team_key --check team.key    validate a key file and print its fingerprint
// Copy the same file to every robot of the team (docs/team-link.md).

// GCC 12 reports a "potential null pointer dereference" inside libstdc++ when
// it inlines CLI11's string splitting; CLI11 and the standard headers are first
// included here, so this silences only them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <CLI/CLI.hpp>
#pragma GCC diagnostic pop

#include <cstdio>
#include <string>

#include "p3at/common/cli_exit.hpp"
#include "p3at/team_link/team_key.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Creates the team key file (32 random bytes as 64 hex characters, mode 0600) that authenticates\n"
      "team-link messages, or checks one. Every robot of a team needs the same file; compare\n"
      "fingerprints to check without showing the key."};
  std::string path;
  bool force = false;
  bool check = false;
  app.add_option("FILE", path, "Key file to write (or to check with --check)")->required();
  app.add_flag("--force", force, "Replace an existing key file");
  app.add_flag("--check", check, "Only validate FILE and print its fingerprint");
  P3AT_CLI_PARSE(app, argc, argv);

  if (check) {
    auto key = p3at::hal::load_team_key(path);
    if (!key) {
      std::fprintf(stderr, "p3at_team_key: %s\n", key.error().message.c_str());
      return 1;
    }
    std::printf("[p3at_team_key] file=%s valid=1 fingerprint=%s\n", path.c_str(),
                p3at::hal::team_key_fingerprint(key.value()).c_str());
    return 0;
  }
  auto key = p3at::hal::generate_team_key();
  if (!key) {
    std::fprintf(stderr, "p3at_team_key: %s\n", key.error().message.c_str());
    return 1;
  }
  if (auto s = p3at::hal::write_team_key_file(path, key.value(), force); !s) {
    std::fprintf(stderr, "p3at_team_key: %s\n", s.error().message.c_str());
    return 1;
  }
  std::printf("[p3at_team_key] wrote=%s mode=0600 fingerprint=%s\n", path.c_str(),
              p3at::hal::team_key_fingerprint(key.value()).c_str());
  return 0;
}
