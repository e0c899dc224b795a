#include "p3at/launch_gate/team_agreement.hpp"

#include <algorithm>
#include <utility>

#include "p3at/launch_gate/check_report.hpp"
#include "p3at/launch_gate/launch_session.hpp"

namespace p3at::gate {

namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
  return out;
}

std::string no_go_reason(const hal::GateVerdict& v) {
  // A teammate's refusal carries p_joint >= threshold and its reason in detail.
  std::string why = v.p_joint < v.threshold
                        ? "P(success) " + fixed(v.p_joint, 4) + " < threshold " + fixed(v.threshold, 4)
                        : std::string();
  if (!v.detail.empty()) why += (why.empty() ? "" : " (") + v.detail + (why.empty() ? "" : ")");
  return why;
}

}  // namespace

const char* to_string(AgreementState state) {
  switch (state) {
    case AgreementState::waiting: return "waiting";
    case AgreementState::launch: return "launch";
    case AgreementState::no_go: return "no-go";
    case AgreementState::mismatch: return "mismatch";
    case AgreementState::silent: return "silent";
    case AgreementState::in_doubt: return "in-doubt";
  }
  return "?";
}

TeamAgreement::TeamAgreement(hal::GateVerdict own, std::vector<std::string> roster, std::int64_t start_us,
                             std::int64_t timeout_us, std::int64_t doubt_us)
    : own_(std::move(own)), start_us_(start_us), timeout_us_(timeout_us), doubt_us_(doubt_us) {
  own_.session.clear();
  own_.heard.clear();
  published_ = own_;
  for (std::string& name : roster) {
    if (name != own_.robot) teammates_.push_back(std::move(name));
  }
}

bool TeamAgreement::is_current(const hal::GateVerdict& v) const {
  return std::any_of(v.heard.begin(), v.heard.end(), [&](const hal::HeardNonce& h) {
    return h.robot == own_.robot && h.nonce == own_.nonce;
  });
}

void TeamAgreement::observe(const std::vector<hal::GateVerdict>& teammates) {
  published_.heard.clear();
  for (const std::string& name : teammates_) {
    const auto it = std::find_if(teammates.begin(), teammates.end(),
                                 [&](const hal::GateVerdict& v) { return v.robot == name; });
    if (it != teammates.end() && !it->nonce.empty()) published_.heard.push_back({name, it->nonce});
  }
}

void TeamAgreement::decide(AgreementState state, std::string reason) {
  agreement_.state = state;
  agreement_.reason = std::move(reason);
  if (state == AgreementState::no_go || state == AgreementState::mismatch || state == AgreementState::silent) {
    // Tell the team why; never go on publishing the earlier GO.
    if (own_.decision != hal::GateDecision::no_go) {
      published_.decision = hal::GateDecision::no_go;
      published_.detail = "refused: " + agreement_.reason;
    }
    published_.session.clear();
  }
}

const Agreement& TeamAgreement::update(std::int64_t now_us, const std::vector<hal::GateVerdict>& teammates) {
  observe(teammates);
  if (decided()) return agreement_;
  agreement_.team.assign(1, own_);
  agreement_.silent.clear();
  agreement_.deaf.clear();
  std::vector<const hal::GateVerdict*> heard;
  for (const std::string& name : teammates_) {
    const auto it = std::find_if(teammates.begin(), teammates.end(),
                                 [&](const hal::GateVerdict& v) { return v.robot == name; });
    // Once committed, only the teammate processes committed with count: a
    // restarted teammate (another nonce) is a stranger to this session.
    const bool usable = it != teammates.end() && is_current(*it) &&
                        (!agreement_.committed || committed_nonces_[name] == it->nonce);
    if (!usable) {
      agreement_.silent.push_back(name);
      if (it != teammates.end()) agreement_.deaf.push_back(name);
    } else {
      heard.push_back(&*it);
      agreement_.team.push_back(*it);
    }
  }

  if (own_.decision == hal::GateDecision::no_go) {
    decide(AgreementState::no_go, "this robot's verdict is NO-GO: P(success) " + fixed(own_.p_joint, 4) +
                                      " < threshold " + fixed(own_.threshold, 4) +
                                      (own_.detail.empty() ? "" : " (" + own_.detail + ")"));
    return agreement_;
  }
  for (const hal::GateVerdict* v : heard) {
    if (v->mission_hash != own_.mission_hash) {
      decide(AgreementState::mismatch, "teammate " + v->robot + " verified a different mission or models (hash " +
                                           v->mission_hash.substr(0, 16) + "…, ours " +
                                           own_.mission_hash.substr(0, 16) + "…)");
      return agreement_;
    }
  }
  for (const hal::GateVerdict* v : heard) {
    if (v->decision == hal::GateDecision::no_go) {
      decide(AgreementState::no_go, "teammate " + v->robot + " says NO-GO: " + no_go_reason(*v));
      return agreement_;
    }
  }
  if (!agreement_.committed && agreement_.silent.empty()) {
    std::vector<hal::HeardNonce> nonces{{own_.robot, own_.nonce}};
    for (const hal::GateVerdict* v : heard) {
      nonces.push_back({v->robot, v->nonce});
      committed_nonces_[v->robot] = v->nonce;
    }
    agreement_.committed = true;
    agreement_.session = launch_session_id(own_.mission_hash, nonces);
    published_.session = agreement_.session;
  }
  if (agreement_.committed && agreement_.silent.empty() &&
      std::all_of(heard.begin(), heard.end(),
                  [&](const hal::GateVerdict* v) { return v->session == agreement_.session; })) {
    std::string votes;
    for (const hal::GateVerdict& v : agreement_.team) {
      votes += (votes.empty() ? "" : ",") + v.robot + ":" + hal::to_string(v.decision);
    }
    decide(AgreementState::launch, "every robot agrees: " + votes + " session=" + agreement_.session.substr(0, 16));
    return agreement_;
  }
  const std::int64_t waited_us = now_us - start_us_;
  if (!agreement_.committed && waited_us >= timeout_us_) {
    std::string reason = "no verdict from " + join(agreement_.silent) + " within " +
                         fixed(static_cast<double>(timeout_us_) / 1e6, 1) + " s";
    if (!agreement_.deaf.empty()) reason += " (heard " + join(agreement_.deaf) + ", but not hearing this robot)";
    decide(AgreementState::silent, std::move(reason));
  } else if (agreement_.committed && waited_us >= timeout_us_ + doubt_us_) {
    std::vector<std::string> uncommitted;
    for (const hal::GateVerdict* v : heard) {
      if (v->session != agreement_.session) uncommitted.push_back(v->robot);
    }
    for (const std::string& n : agreement_.silent) uncommitted.push_back(n);
    decide(AgreementState::in_doubt, "committed to session " + agreement_.session.substr(0, 16) +
                                         " but did not hear the commitment of " + join(uncommitted) + " within " +
                                         fixed(static_cast<double>(timeout_us_ + doubt_us_) / 1e6, 1) +
                                         " s; a teammate may have launched; this robot does not move");
  }
  return agreement_;
}

}  // namespace p3at::gate
