// libFuzzer target for the mission loader: any input either loads or throws
// MissionError (never anything else, never a crash), and whatever loads
// prints to canonical YAML that parses back to the same mission.

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "p3at/mission/loader.hpp"
#include "p3at/mission/printer.hpp"

namespace {

bool loads(std::string_view text, p3at::mission::Mission& mission) {
  try {
    mission = p3at::mission::parse_mission(text, "fuzz.yaml");
    return true;
  } catch (const p3at::mission::MissionError& e) {
    // Every rejection says what was wrong.
    if (e.detail().empty()) std::abort();
    return false;
  }
}

}  // namespace

// yaml-cpp builds its scanner's tables in function-local statics on first use.
// Touching most scanner paths once here keeps those one-time allocations out
// of the fuzzed runs, where libFuzzer would take them for leaks.
extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  constexpr std::string_view kWarmUp[] = {
      "%YAML 1.2\n---\na: &x [1, 'two', \"th\\tree\", {k: v}]\nb: *x\nc: !!str 5\nd: |\n  lit\ne: >\n  fold\n...\n",
      "? complex\n: value\n- bad\n",
      "a: [1, 2\n",
      "a: {b: 1\n",
      "a: 'unterminated\n",
      "a: \"bad \\q escape\"\n",
      "a: b: c\n",
      "\t- tab\n",
      "--- !tag &anchor\n# comment\n- - nested\n  - seq\n- ~\n- null\n- true\n- 0x1F\n- .inf\n",
      "a:\n  - 1\n - 2\n",
      "[a, b]: c\n*undefined\n",
  };
  p3at::mission::Mission mission;
  for (std::string_view text : kWarmUp) (void)loads(text, mission);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);  // bytes as text
  p3at::mission::Mission mission;
  if (!loads(text, mission)) return 0;
  // The canonical form of a valid mission must load, and mean the same mission.
  p3at::mission::Mission again;
  if (!loads(p3at::mission::to_yaml(mission), again) || !(again == mission)) std::abort();
  return 0;
}
