#include "yaml_tree.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/exceptions.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>

#include "rondo/core/utf8.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

namespace rondo::detail {

Json plain_scalar(const std::string& s) {
  if (s.empty() || s == "~" || s == "null" || s == "Null" || s == "NULL") return nullptr;
  if (s == "true" || s == "True" || s == "TRUE") return true;
  if (s == "false" || s == "False" || s == "FALSE") return false;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (*first == '+') ++first;
  std::int64_t i = 0;
  if (auto [p, ec] = std::from_chars(first, last, i); ec == std::errc{} && p == last) return i;
  // Only text that looks like a number is tried as a float, so "1h30m" or "inf-ish" stay strings.
  bool numeric = first != last;
  for (const char* c = first; c != last && numeric; ++c) {
    numeric = (std::isdigit(static_cast<unsigned char>(*c)) != 0) || *c == '.' || *c == 'e' || *c == 'E' || *c == '-' ||
              *c == '+';
  }
  if (numeric) {
    double d = 0;
    if (auto [p, ec] = std::from_chars(first, last, d); ec == std::errc{} && p == last && std::isfinite(d)) {
      return d;
    }
  }
  return s;
}

namespace {

std::string join_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
std::string join_index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// Thrown from an event handler to stop yaml-cpp's parser with our own error.
struct Stop {
  Error error;
};

// What an anchor names, kept so that each alias to it can be checked before it is copied.
struct Anchored {
  Json value;
  std::optional<std::string> scalar_text;  // a scalar's text as written, for use as a key
  std::size_t values = 1;                  // values in the subtree, aliases expanded
  int height = 0;                          // collection levels in the subtree (0 for a scalar)
  int alias_depth = 0;                     // aliases nested inside the subtree's anchors
};

class TreeBuilder : public YAML::EventHandler {
 public:
  TreeBuilder(const std::string& source, std::map<std::string, int>& lines) : source_(source), lines_(lines) {}

  Json take() { return std::move(root_); }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}

  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    add(mark, anchor, Anchored{Json(nullptr), std::nullopt}, /*counted=*/false);
  }

  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    // The text is UTF-8, but an escape in a double-quoted scalar ("\\uD800") can still make a
    // surrogate, which is not (found by fuzz_world and fuzz_requests).
    if (first_invalid_utf8(value)) fail(mark, "a quoted string is not valid UTF-8 (an escaped surrogate?)");
    // "!" is the tag of a quoted scalar: it stays text whatever it says.
    const bool text = tag == "!" || tag == "tag:yaml.org,2002:str";
    add(mark, anchor, Anchored{text ? Json(value) : plain_scalar(value), value}, /*counted=*/false);
  }

  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (++aliases_ > Document::kMaxAliases) {
      fail(mark, "more than " + std::to_string(Document::kMaxAliases) + " aliases (the limit is " +
                     std::to_string(Document::kMaxAliases) + ")");
    }
    if (anchor >= anchors_.size() || !anchors_[anchor]) fail(mark, "an alias refers to a collection that contains it");
    const Anchored& a = *anchors_[anchor];
    if (a.alias_depth + 1 > Document::kMaxAliasDepth) {
      fail(mark, "aliases nest more than " + std::to_string(Document::kMaxAliasDepth) + " deep (the limit is " +
                     std::to_string(Document::kMaxAliasDepth) + ")");
    }
    count(mark, a.values);
    if (a.height > 0 && static_cast<int>(stack_.size()) + a.height > Document::kMaxDepth) {
      fail(mark, "nested deeper than " + std::to_string(Document::kMaxDepth) + " levels");
    }
    Anchored copy = a;
    copy.alias_depth = a.alias_depth + 1;
    add(mark, 0, std::move(copy), /*counted=*/true);
  }

  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, anchor, Json::array());
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, anchor, Json::object());
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    Json value;
    std::string path;
    std::optional<std::string> key;  // in a mapping: the key whose value comes next
    YAML::anchor_t anchor = 0;
    std::size_t values_before = 0;
    YAML::Mark mark;
    int child_height = 0;
    int alias_depth = 0;
  };

  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& what) const {
    throw Stop{Error::invalid(source_ + ":" + std::to_string(mark.line + 1) + ": " + what)};
  }

  void count(const YAML::Mark& mark, std::size_t n) {
    values_ += n;
    if (values_ > Document::kMaxValues) {
      fail(mark, "more than " + std::to_string(Document::kMaxValues) +
                     " values once aliases are expanded (the limit is " + std::to_string(Document::kMaxValues) + ")");
    }
  }

  bool expecting_key() const { return !stack_.empty() && stack_.back().value.is_object() && !stack_.back().key; }

  // The path of the value that comes next, recording its line.
  std::string next_path(const YAML::Mark& mark) {
    std::string path;
    if (!stack_.empty()) {
      const Frame& top = stack_.back();
      path = top.value.is_object() ? join_key(top.path, *top.key) : join_index(top.path, top.value.size());
    }
    if (mark.line >= 0) lines_[path] = mark.line + 1;
    return path;
  }

  void remember(YAML::anchor_t anchor, const Anchored& a) {
    if (anchor == 0) return;
    if (anchors_.size() <= anchor) anchors_.resize(anchor + 1);
    anchors_[anchor] = a;
  }

  void add(const YAML::Mark& mark, YAML::anchor_t anchor, Anchored a, bool counted) {
    if (!counted) count(mark, 1);
    if (expecting_key()) {
      Frame& top = stack_.back();
      if (!a.scalar_text) fail(mark, "keys must be plain text");
      const std::string& key = *a.scalar_text;
      if (top.value.contains(key)) fail(mark, join_key(top.path, key) + ": duplicate key '" + key + "'");
      remember(anchor, a);
      top.key = key;
      return;
    }
    next_path(mark);
    remember(anchor, a);
    attach(std::move(a.value), a.height, a.alias_depth);
  }

  void attach(Json value, int height, int alias_depth) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return;
    }
    Frame& top = stack_.back();
    if (top.value.is_object()) {
      top.value[*top.key] = std::move(value);
      top.key.reset();
    } else {
      top.value.push_back(std::move(value));
    }
    top.child_height = std::max(top.child_height, height);
    top.alias_depth = std::max(top.alias_depth, alias_depth);
  }

  void open(const YAML::Mark& mark, YAML::anchor_t anchor, Json empty) {
    if (expecting_key()) fail(mark, "keys must be plain text");
    std::string path = next_path(mark);
    if (stack_.size() >= static_cast<std::size_t>(Document::kMaxDepth)) {
      fail(mark,
           (path.empty() ? "" : path + ": ") + "nested deeper than " + std::to_string(Document::kMaxDepth) + " levels");
    }
    count(mark, 1);
    if (anchor != 0 && anchors_.size() > anchor) anchors_[anchor].reset();  // open: not yet usable
    stack_.push_back(Frame{std::move(empty), std::move(path), std::nullopt, anchor, values_ - 1, mark, 0, 0});
  }

  void close() {
    Frame f = std::move(stack_.back());
    stack_.pop_back();
    const int height = f.child_height + 1;
    if (f.anchor != 0) {
      // The anchor keeps a copy of the collection, which counts against the same budget.
      const std::size_t values = values_ - f.values_before;
      count(f.mark, values);
      remember(f.anchor, Anchored{f.value, std::nullopt, values, height, f.alias_depth});
    }
    attach(std::move(f.value), height, f.alias_depth);
  }

  const std::string& source_;
  std::map<std::string, int>& lines_;
  std::vector<Frame> stack_;
  std::vector<std::optional<Anchored>> anchors_;  // by yaml-cpp's anchor number (from 1)
  std::size_t values_ = 0;
  std::size_t aliases_ = 0;
  Json root_ = nullptr;
};

}  // namespace

Result<Json> yaml_to_json(std::string_view text, const std::string& source, std::map<std::string, int>& lines) {
  std::istringstream in{std::string(text)};
  TreeBuilder builder(source, lines);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(builder);  // only the first document, as YAML::Load reads
  } catch (const Stop& stop) {
    return stop.error;
  } catch (const YAML::Exception& e) {
    return Error::invalid(source + ":" + std::to_string(e.mark.line + 1) + ": " + quote_for_message(e.msg, 400));
  }
  return builder.take();
}

}  // namespace rondo::detail
