#include "p3at/common/yaml_document.hpp"

#include <yaml-cpp/eventhandler.h>

#include <array>
#include <sstream>

namespace p3at::yaml_document {
namespace {

// Follows the document stream's events to learn, per document, where its root
// starts and whether it is null: enough to find the one real document, and to
// notice yaml-cpp 0.7 making no progress.
class RootEvents : public YAML::EventHandler {
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

}  // namespace

YAML::Node load_single(std::string_view text, const std::string& empty_detail) {
  const std::string buffer(text);
  try {
    // Walk the events first: yaml-cpp 0.7 reports an endless run of null
    // documents, never consuming a stray ',' outside a flow collection, so
    // LoadAll would not return. Two null documents at the same position are
    // that loop, reported as the malformed input it is.
    std::istringstream events_in(buffer);
    YAML::Parser parser(events_in);
    RootEvents events;
    bool found = false;
    bool have_previous = false;
    RootEvents::Root previous;
    while (parser.HandleNextDocument(events)) {
      const RootEvents::Root root = events.root();
      if (have_previous && root.is_null && previous.is_null && root.mark.pos == previous.mark.pos) {
        const auto pos = static_cast<std::size_t>(root.mark.pos);
        throw Problem{root.mark, "malformed YAML: unexpected " + (pos < buffer.size()
                                                                      ? "'" + show(buffer.substr(pos, 1)) + "'"
                                                                      : std::string("end of input"))};
      }
      if (!root.is_null) {
        if (found) throw Problem{root.mark, "expected a single YAML document, found a second one"};
        found = true;
      }
      previous = root;
      have_previous = true;
    }
    if (!found) throw Problem{YAML::Mark(), empty_detail};
    // The stream is known to end and to hold one non-empty document.
    for (const YAML::Node& document : YAML::LoadAll(buffer)) {
      if (!document.IsNull()) return document;
    }
    throw Problem{YAML::Mark(), empty_detail};
  } catch (const YAML::Exception& e) {
    throw Problem{e.mark, "malformed YAML: " + e.msg};
  }
}

std::string show(std::string_view text, std::size_t max_chars) {
  std::string out;
  for (char c : text.substr(0, max_chars)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte >= 0x7f) {
      constexpr std::array<char, 17> kHex{"0123456789abcdef"};
      out += "\\x";
      out += kHex[byte >> 4U];
      out += kHex[byte & 0xFU];
    } else {
      out += c;
    }
  }
  if (text.size() > max_chars) out += "...";
  return out;
}

}  // namespace p3at::yaml_document
