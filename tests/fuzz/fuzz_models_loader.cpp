// libFuzzer target for the robot-models loader: any input either loads or
// throws ModelsError (never anything else, never a crash), and whatever loads
// is written back by write_models() to a file that loads to the same values.
// `walls_from` paths resolve against the Bounding Overwatch example's folder,
// so seeds naming world.yaml reach the walls_from reader too.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "p3at/verifier/models.hpp"

namespace {

using p3at::verifier::Mixture1;
using p3at::verifier::Models;

const std::string kBaseDir = P3AT_FUZZ_MODELS_BASE_DIR;

bool loads(std::string_view text, Models& models) {
  try {
    models = p3at::verifier::parse_models(text, "fuzz.yaml", kBaseDir);
    return true;
  } catch (const p3at::verifier::ModelsError& e) {
    if (e.detail().empty()) std::abort();  // every rejection says what was wrong
    return false;
  }
}

// Equal up to the last few bits (unit conversions round).
bool close(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max(std::abs(a), std::abs(b)); }

bool same(const Mixture1& a, const Mixture1& b) {
  if (a.components.size() != b.components.size()) return false;
  for (std::size_t i = 0; i < a.components.size(); ++i) {
    const auto& x = a.components[i];
    const auto& y = b.components[i];
    if (!close(x.weight, y.weight) || !close(x.mean, y.mean) || !close(x.var, y.var)) return false;
  }
  return true;
}

bool same(const Models& a, const Models& b) {
  if (a.generated_by != b.generated_by || a.robots.size() != b.robots.size()) return false;
  for (std::size_t i = 0; i < a.robots.size(); ++i) {
    const auto& ka = a.robots[i].kinematics;
    const auto& kb = b.robots[i].kinematics;
    const auto& ea = a.robots[i].motion;
    const auto& eb = b.robots[i].motion;
    const bool kinematics = close(ka.cycle_s, kb.cycle_s) && close(ka.max_rot_vel_radps, kb.max_rot_vel_radps) &&
                            close(ka.trans_accel_mps2, kb.trans_accel_mps2) &&
                            close(ka.trans_decel_mps2, kb.trans_decel_mps2) &&
                            close(ka.rot_accel_radps2, kb.rot_accel_radps2) &&
                            close(ka.rot_decel_radps2, kb.rot_decel_radps2) &&
                            close(ka.robot_radius_m, kb.robot_radius_m) && close(ka.rot_gain, kb.rot_gain);
    const bool motion = close(ea.trans_scale, eb.trans_scale) && close(ea.rot_scale, eb.rot_scale) &&
                        close(ea.drift_rad_per_m, eb.drift_rad_per_m) &&
                        close(ea.trans_var_per_m, eb.trans_var_per_m) &&
                        close(ea.rot_var_per_rad, eb.rot_var_per_rad) &&
                        close(ea.heading_var_per_m, eb.heading_var_per_m) &&
                        close(ea.trans_rel_var, eb.trans_rel_var) && close(ea.rot_rel_var, eb.rot_rel_var);
    if (a.robots[i].name != b.robots[i].name || !kinematics || !motion) return false;
  }
  return same(a.comm.delivery_s, b.comm.delivery_s) && same(a.comm.ack_s, b.comm.ack_s) &&
         a.environment == b.environment && a.budget == b.budget;
}

}  // namespace

// yaml-cpp builds its scanner's tables in function-local statics on first use;
// touching most scanner paths here keeps those one-time allocations out of the
// fuzzed runs, where libFuzzer would take them for leaks.
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
      "models: {version: 1}\nrobots: [{name: r}]\nenvironment: {walls_from: world.yaml}\n",
  };
  Models models;
  for (std::string_view text : kWarmUp) (void)loads(text, models);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);  // bytes as text
  Models models;
  if (!loads(text, models)) return 0;
  // What loads must write, and the written file must load to the same values.
  Models again;
  if (!loads(p3at::verifier::write_models(models), again) || !same(models, again)) std::abort();
  return 0;
}
