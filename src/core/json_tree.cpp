#include "json_tree.h"

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <set>
#include <vector>

#include "rondo/core/utf8.h"

namespace rondo::detail {
namespace {

std::string join_key(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}
std::string join_index(const std::string& parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// A character iterator that notes how far nlohmann's lexer has read: its parse callback is given
// no position, so this is how the callback learns the line it is on. The lexer reads one character
// at a time and never ahead of the token it hands over, so when a key reaches the callback the
// reader is just past the key's closing quote, on the key's own line.
class ReadingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  ReadingIterator(const char* at, const char** furthest) : at_(at), furthest_(furthest) {}
  reference operator*() const { return *at_; }
  ReadingIterator& operator++() {
    *furthest_ = ++at_;
    return *this;
  }
  ReadingIterator operator++(int) {
    ReadingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const ReadingIterator& other) const { return at_ == other.at_; }

 private:
  const char* at_;
  const char** furthest_;
};

// Thrown from the parse callback to stop the parse with our own error.
struct Stop {
  Error error;
};

// Follows the parse callback's events: the path of the value being read, for messages, and the keys
// each open object has had so far.
class KeyWatch {
 public:
  KeyWatch(std::string_view text, const std::string& source, const char** furthest)
      : text_(text), source_(source), furthest_(furthest) {}

  bool on_event(int depth, Json::parse_event_t event, const Json& parsed) {
    using Event = Json::parse_event_t;
    if (depth >= Document::kMaxDepth) {  // depth counts from 0
      stop(": nested deeper than " + std::to_string(Document::kMaxDepth) + " levels");
    }
    if (event == Event::value || event == Event::object_start || event == Event::array_start) {
      if (++values_ > Document::kMaxValues) {
        stop(": more than " + std::to_string(Document::kMaxValues) + " values (the limit is " +
             std::to_string(Document::kMaxValues) + ")");
      }
    }
    switch (event) {
      case Event::object_start:
      case Event::array_start:
        open_.push_back(Open{.path = next_path(), .object = event == Event::object_start});
        break;
      case Event::key: {
        Open& object = open_.back();
        object.key = parsed.get_ref<const std::string&>();
        if (!object.keys.insert(object.key).second) {
          stop(":" + std::to_string(line()) + ": " + quote_for_message(join_key(object.path, object.key), 200) +
               ": duplicate key '" + quote_for_message(object.key) + "'");
        }
        break;
      }
      case Event::value:
        value_done();
        break;
      case Event::object_end:
      case Event::array_end:
        open_.pop_back();
        value_done();
        break;
    }
    return true;
  }

 private:
  struct Open {
    std::string path;
    bool object = false;
    std::string key{};                          // an object's key whose value comes next
    std::set<std::string, std::less<>> keys{};  // an object's keys so far
    std::size_t items = 0;                      // an array's items so far
  };

  [[noreturn]] void stop(const std::string& what) const { throw Stop{Error::invalid(source_ + what)}; }

  int line() const {
    const std::size_t read = static_cast<std::size_t>(*furthest_ - text_.data());
    return 1 + static_cast<int>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(read), '\n'));
  }

  std::string next_path() const {
    if (open_.empty()) return "";
    const Open& top = open_.back();
    return top.object ? join_key(top.path, top.key) : join_index(top.path, top.items);
  }

  void value_done() {
    if (!open_.empty() && !open_.back().object) ++open_.back().items;
  }

  std::string_view text_;
  const std::string& source_;
  const char** furthest_;
  std::vector<Open> open_;
  std::size_t values_ = 0;
};

}  // namespace

Result<Json> json_to_tree(std::string_view text, const std::string& source) {
  const char* furthest = text.data();
  KeyWatch watch(text, source, &furthest);
  try {
    return Json::parse(
        ReadingIterator(text.data(), &furthest), ReadingIterator(text.data() + text.size(), &furthest),
        [&watch](int depth, Json::parse_event_t event, Json& parsed) { return watch.on_event(depth, event, parsed); });
  } catch (const Stop& stop) {
    return stop.error;
  } catch (const Json::exception& e) {
    // nlohmann's message names the byte and line: "parse error at line 3, column 5: ..."
    return Error::invalid(source + ": " + quote_for_message(e.what(), 400));
  }
}

}  // namespace rondo::detail
