#include "p3at/launch_gate/team_agreement.hpp"

#include <algorithm>
#include <utility>

#include "p3at/launch_gate/check_report.hpp"

namespace p3at::gate {

const char* to_string(AgreementState state) {
  switch (state) {
    case AgreementState::waiting: return "waiting";
    case AgreementState::launch: return "launch";
    case AgreementState::no_go: return "no-go";
    case AgreementState::mismatch: return "mismatch";
    case AgreementState::silent: return "silent";
  }
  return "?";
}

TeamAgreement::TeamAgreement(gate::GateVerdict own, std::vector<std::string> roster, std::int64_t start_us,
                             std::int64_t timeout_us)
    : own_(std::move(own)), start_us_(start_us), timeout_us_(timeout_us) {
  for (std::string& name : roster) {
    if (name != own_.robot) teammates_.push_back(std::move(name));
  }
}

void TeamAgreement::decide(AgreementState state, std::string reason) {
  agreement_.state = state;
  agreement_.reason = std::move(reason);
}

const Agreement& TeamAgreement::update(std::int64_t now_us, const std::vector<gate::GateVerdict>& teammates) {
  if (decided()) return agreement_;
  agreement_.team.assign(1, own_);
  agreement_.silent.clear();
  std::vector<const gate::GateVerdict*> heard;
  for (const std::string& name : teammates_) {
    const auto it = std::find_if(teammates.begin(), teammates.end(),
                                 [&](const gate::GateVerdict& v) { return v.robot == name; });
    if (it == teammates.end()) {
      agreement_.silent.push_back(name);
    } else {
      heard.push_back(&*it);
      agreement_.team.push_back(*it);
    }
  }

  if (own_.decision == gate::GateDecision::no_go) {
    decide(AgreementState::no_go, "this robot's verdict is NO-GO: P(success) " + fixed(own_.p_joint, 4) +
                                      " < threshold " + fixed(own_.threshold, 4) +
                                      (own_.detail.empty() ? "" : " (" + own_.detail + ")"));
    return agreement_;
  }
  for (const gate::GateVerdict* v : heard) {
    if (v->mission_hash != own_.mission_hash) {
      decide(AgreementState::mismatch, "teammate " + v->robot + " verified a different mission or models (hash " +
                                           v->mission_hash.substr(0, 16) + "…, ours " +
                                           own_.mission_hash.substr(0, 16) + "…)");
      return agreement_;
    }
  }
  for (const gate::GateVerdict* v : heard) {
    if (v->decision == gate::GateDecision::no_go) {
      decide(AgreementState::no_go, "teammate " + v->robot + " says NO-GO: P(success) " + fixed(v->p_joint, 4) +
                                        " < threshold " + fixed(v->threshold, 4) +
                                        (v->detail.empty() ? "" : " (" + v->detail + ")"));
      return agreement_;
    }
  }
  if (agreement_.silent.empty()) {
    std::string votes;
    for (const gate::GateVerdict& v : agreement_.team) {
      votes += (votes.empty() ? "" : ",") + v.robot + ":" + gate::to_string(v.decision);
    }
    decide(AgreementState::launch, "every robot agrees: " + votes);
    return agreement_;
  }
  if (now_us - start_us_ >= timeout_us_) {
    std::string names;
    for (const std::string& n : agreement_.silent) names += (names.empty() ? "" : ",") + n;
    decide(AgreementState::silent, "no verdict from " + names + " within " +
                                       fixed(static_cast<double>(timeout_us_) / 1e6, 1) + " s");
  }
  return agreement_;
}

}  // namespace p3at::gate
