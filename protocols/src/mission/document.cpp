#include "document.hpp"

#include <yaml-cpp/eventhandler.h>

#include <sstream>
#include <string>

namespace p3at::mission::detail {
namespace {

// Records where each document's root node starts and whether it is null.
class RootRecorder : public YAML::EventHandler {
 public:
  struct Root {
    YAML::Mark mark;
    bool is_null = true;
  };

  void OnDocumentStart(const YAML::Mark& mark) override {
    root_ = Root{mark, true};
    depth_ = 0;
  }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, true); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { node(mark, false); }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t, const std::string&) override {
    node(mark, false);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    node(mark, false);
    ++depth_;
  }
  void OnSequenceEnd() override { --depth_; }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t, YAML::EmitterStyle::value) override {
    node(mark, false);
    ++depth_;
  }
  void OnMapEnd() override { --depth_; }

  const Root& root() const { return root_; }

 private:
  void node(const YAML::Mark& mark, bool is_null) {
    if (depth_ == 0) root_ = Root{mark, is_null};
  }

  Root root_;
  int depth_ = 0;
};

const char* const kEmpty = "empty mission (expected a mapping with keys mission, criteria, robots, messages)";

}  // namespace

YAML::Node load_single_document(const Source& src, std::string_view text) {
  const std::string buffer(text);
  try {
    // First walk the event stream: yaml-cpp 0.7 can report an endless run of
    // null documents without consuming a stray token (a ',' outside any
    // flow collection), so LoadAll would never return; here no progress
    // between two documents is caught and reported instead.
    std::istringstream events_in(buffer);
    YAML::Parser parser(events_in);
    RootRecorder recorder;
    bool have_mission = false;
    bool have_previous = false;
    RootRecorder::Root previous;
    while (parser.HandleNextDocument(recorder)) {
      const RootRecorder::Root root = recorder.root();
      if (have_previous && root.is_null && previous.is_null && root.mark.pos == previous.mark.pos) {
        const auto pos = static_cast<std::size_t>(root.mark.pos);
        const std::string token = pos < buffer.size() ? "'" + show(buffer.substr(pos, 1)) + "'" : "end of input";
        src.fail(root.mark, "malformed YAML: unexpected " + token);
      }
      if (!root.is_null) {
        if (have_mission) src.fail(root.mark, "expected a single YAML document, found a second one");
        have_mission = true;
      }
      previous = root;
      have_previous = true;
    }
    if (!have_mission) src.fail(YAML::Mark(), kEmpty);

    // The stream is now known to end, and to hold one non-empty document
    // (and maybe empty ones around it); build its nodes.
    for (const YAML::Node& document : YAML::LoadAll(buffer)) {
      if (!document.IsNull()) return document;
    }
    src.fail(YAML::Mark(), kEmpty);
  } catch (const YAML::Exception& e) {
    src.fail(e.mark, "malformed YAML: " + e.msg);
  }
}

}  // namespace p3at::mission::detail
