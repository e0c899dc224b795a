#include "p3at/sim/can/node_commands.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

namespace p3at::can_sim {
namespace {

Error bad(std::string_view line, const std::string& what) {
  return make_error(Error::Code::invalid_argument, "command '" + std::string(line) + "': " + what);
}

Result<bool> on_off(std::string_view line, const std::vector<std::string>& words) {
  if (words.size() == 2 && (words[1] == "on" || words[1] == "1")) return true;
  if (words.size() == 2 && (words[1] == "off" || words[1] == "0")) return false;
  return bad(line, "expected '" + words[0] + " on' or '" + words[0] + " off'");
}

}  // namespace

const char* command_help() {
  return "commands on stdin, one per line:\n"
         "  estop on|off        press / release the e-stop button\n"
         "  bumpers MASK        bumper segments pressed (0..255, bits 0-3 front, 4-7 rear; 0 = none)\n"
         "  fault on|off        the safety node's fault flag and EMCY 0xFF01 / error reset\n"
         "  silent on|off       the safety node stops / resumes transmitting (lost node)\n"
         "  gyro-fault on|off   the gyro's fault bit and EMCY 0x5000 / error reset\n"
         "  gyro-silent on|off  the gyro stops / resumes transmitting\n"
         "  rate RADPS          the true yaw rate the gyro measures\n"
         "  reboot              both nodes power-cycle (boot-up, pre-operational)\n"
         "  quit                exit\n";
}

Result<CommandEffect> apply_command(std::string_view line, sim::SimAccessories& nodes) {
  std::vector<std::string> words;
  std::istringstream in{std::string(line)};
  for (std::string w; in >> w;) words.push_back(w);
  CommandEffect effect;
  if (words.empty() || words[0].front() == '#') return effect;
  const std::string& cmd = words[0];
  if (cmd == "quit" || cmd == "exit") {
    effect.quit = true;
    return effect;
  }
  if (cmd == "reboot") {
    nodes.gyro().reboot();
    nodes.safety().reboot();
    return effect;
  }
  if (cmd == "rate" || cmd == "bumpers") {
    if (words.size() != 2) return bad(line, "expected '" + cmd + " VALUE'");
    errno = 0;
    char* end = nullptr;
    if (cmd == "rate") {
      const double v = std::strtod(words[1].c_str(), &end);
      if (end == words[1].c_str() || *end != '\0' || !std::isfinite(v) || errno != 0) {
        return bad(line, "'" + words[1] + "' is not a number (rad/s)");
      }
      effect.has_rate = true;
      effect.rate_radps = v;
      return effect;
    }
    const long v = std::strtol(words[1].c_str(), &end, 0);
    if (end == words[1].c_str() || *end != '\0' || v < 0 || v > 255) {
      return bad(line, "'" + words[1] + "' is not a bumper mask 0..255 (e.g. 0x01)");
    }
    nodes.safety().set_bumpers(static_cast<std::uint8_t>(v));
    return effect;
  }
  if (cmd == "estop" || cmd == "fault" || cmd == "silent" || cmd == "gyro-fault" || cmd == "gyro-silent") {
    auto on = on_off(line, words);
    if (!on) return on.error();
    if (cmd == "estop") nodes.safety().press_estop(*on);
    if (cmd == "fault") nodes.safety().set_fault(*on);
    if (cmd == "silent") nodes.safety().set_silent(*on);
    if (cmd == "gyro-fault") nodes.gyro().set_fault(*on);
    if (cmd == "gyro-silent") nodes.gyro().set_silent(*on);
    return effect;
  }
  return bad(line, "unknown command (try estop, bumpers, fault, silent, gyro-fault, gyro-silent, rate, reboot, quit)");
}

}  // namespace p3at::can_sim
