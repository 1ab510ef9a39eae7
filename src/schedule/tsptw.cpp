#include "rondo/schedule/tsptw.h"

#include <charconv>
#include <map>

#include <fmt/format.h>

#include "rondo/core/document.h"
#include "rondo/core/utf8.h"

namespace rondo::schedule {

namespace {

// Limits before work (docs/hardening.md): the file's size, and each time or weight in seconds.
constexpr std::size_t kMaxTsptwBytes = 64u << 20;
constexpr std::int64_t kMaxTsptwValue = 1'000'000'000;  // 10^9 s (31 years): a sum of 100000 fits in ms

struct Token {
  std::string_view text;
  int line;
};

// Splits into whitespace-separated tokens, remembering their line; "KEY:" and ":" are split too.
std::vector<Token> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  int line = 1;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (c == ' ' || c == '\t' || c == '\r') {
      ++i;
    } else if (c == ':') {
      tokens.push_back({text.substr(i, 1), line});
      ++i;
    } else {
      std::size_t j = i;
      while (j < text.size() && text[j] != ' ' && text[j] != '\t' && text[j] != '\r' && text[j] != '\n' &&
             text[j] != ':')
        ++j;
      tokens.push_back({text.substr(i, j - i), line});
      i = j;
    }
  }
  return tokens;
}

class Reader {
 public:
  Reader(std::vector<Token> tokens, std::string source) : tokens_(std::move(tokens)), source_(std::move(source)) {}
  bool done() const { return at_ >= tokens_.size(); }
  std::size_t remaining() const { return tokens_.size() - at_; }
  const Token& peek() const { return tokens_[at_]; }
  Token next() { return tokens_[at_++]; }
  int line() const { return done() ? (tokens_.empty() ? 1 : tokens_.back().line) : peek().line; }
  Error error(int line, std::string_view what) const {
    return Error::invalid(fmt::format("{}:{}: {}", source_, line, what));
  }
  Result<std::int64_t> integer(std::string_view what) {
    if (done()) return error(line(), fmt::format("{}: unexpected end of file", what));
    const Token t = next();
    std::int64_t v = 0;
    const char* end = t.text.data() + t.text.size();
    auto [ptr, ec] = std::from_chars(t.text.data(), end, v);
    if (ec != std::errc{} || ptr != end)
      return error(t.line, fmt::format("{}: expected an integer, found '{}'", what, quote_for_message(t.text)));
    // Times and weights are whole seconds; past this their milliseconds, and sums of them, overflow.
    if (v > kMaxTsptwValue || v < -kMaxTsptwValue)
      return error(t.line, fmt::format("{}: {} is out of range (at most {} seconds)", what, v, kMaxTsptwValue));
    return v;
  }

 private:
  std::vector<Token> tokens_;
  std::string source_;
  std::size_t at_ = 0;
};

}  // namespace

std::int64_t tsptw_units(Duration d) { return std::chrono::duration_cast<std::chrono::seconds>(d).count(); }

Result<Problem> parse_tsptw(std::string_view text, const std::string& source) {
  Reader r(tokenize(text), source);
  std::int64_t dimension = -1;
  std::vector<std::int64_t> matrix;
  std::vector<std::pair<std::int64_t, std::int64_t>> windows;
  std::vector<bool> window_seen;
  std::int64_t depot = 1;
  bool have_matrix = false, have_windows = false;
  while (!r.done()) {
    const Token key = r.next();
    if (key.text == "EOF") break;
    if (key.text == "EDGE_WEIGHT_SECTION") {
      if (dimension < 0) return r.error(key.line, "EDGE_WEIGHT_SECTION before DIMENSION");
      const auto n = static_cast<std::size_t>(dimension);
      // Each entry is a token of the file: a matrix larger than what is left is refused before
      // anything is allocated for it.
      if (n * n > r.remaining())
        return r.error(key.line, fmt::format("EDGE_WEIGHT_SECTION: DIMENSION {} needs {} entries, the file has only {} "
                                             "tokens left",
                                             dimension, n * n, r.remaining()));
      matrix.resize(n * n);
      for (std::size_t k = 0; k < n * n; ++k) {
        auto v = r.integer(fmt::format("EDGE_WEIGHT_SECTION: entry ({}, {})", k / n + 1, k % n + 1));
        if (!v) return v.error();
        if (*v < 0) return r.error(r.line(), fmt::format("EDGE_WEIGHT_SECTION: negative entry ({}, {})", k / n + 1, k % n + 1));
        matrix[k] = *v;
      }
      have_matrix = true;
      continue;
    }
    if (key.text == "TIME_WINDOW_SECTION") {
      if (dimension < 0) return r.error(key.line, "TIME_WINDOW_SECTION before DIMENSION");
      const auto n = static_cast<std::size_t>(dimension);
      if (3 * n > r.remaining())
        return r.error(key.line, fmt::format("TIME_WINDOW_SECTION: DIMENSION {} needs {} entries, the file has only {} "
                                             "tokens left",
                                             dimension, 3 * n, r.remaining()));
      windows.assign(n, {0, 0});
      window_seen.assign(n, false);
      for (std::size_t k = 0; k < n; ++k) {
        const int line = r.line();
        auto node = r.integer("TIME_WINDOW_SECTION: node");
        if (!node) return node.error();
        if (*node < 1 || *node > dimension)
          return r.error(line, fmt::format("TIME_WINDOW_SECTION: node {} out of range 1..{}", *node, dimension));
        const auto idx = static_cast<std::size_t>(*node - 1);
        if (window_seen[idx]) return r.error(line, fmt::format("TIME_WINDOW_SECTION: node {} listed twice", *node));
        auto ready = r.integer(fmt::format("TIME_WINDOW_SECTION: node {} ready time", *node));
        if (!ready) return ready.error();
        auto due = r.integer(fmt::format("TIME_WINDOW_SECTION: node {} due time", *node));
        if (!due) return due.error();
        if (*due < *ready)
          return r.error(line, fmt::format("TIME_WINDOW_SECTION: node {}: due time {} before ready time {}", *node, *due, *ready));
        windows[idx] = {*ready, *due};
        window_seen[idx] = true;
      }
      have_windows = true;
      continue;
    }
    if (key.text == "DEPOT_SECTION") {
      auto d = r.integer("DEPOT_SECTION");
      if (!d) return d.error();
      depot = *d;
      auto end = r.integer("DEPOT_SECTION: terminating -1");
      if (!end) return end.error();
      if (*end != -1) return r.error(r.line(), "DEPOT_SECTION: only one depot is supported");
      continue;
    }
    // "KEY : value" header lines.
    if (r.done() || r.peek().text != ":")
      return r.error(key.line, fmt::format("unexpected '{}'", quote_for_message(key.text)));
    r.next();
    if (r.done()) return r.error(key.line, fmt::format("{}: missing value", quote_for_message(key.text)));
    const Token value = r.next();
    if (key.text == "DIMENSION") {
      std::int64_t v = 0;
      auto [ptr, ec] = std::from_chars(value.text.data(), value.text.data() + value.text.size(), v);
      if (ec != std::errc{} || ptr != value.text.data() + value.text.size() || v < 1 || v > 100000)
        return r.error(value.line, fmt::format("DIMENSION: expected an integer from 1 to 100000, found '{}'",
                                               quote_for_message(value.text)));
      dimension = v;
    } else if (key.text == "TYPE") {
      if (value.text != "TSPTW")
        return r.error(value.line, fmt::format("TYPE: expected TSPTW, found '{}'", quote_for_message(value.text)));
    } else if (key.text == "EDGE_WEIGHT_TYPE") {
      if (value.text != "EXPLICIT") return r.error(value.line, "EDGE_WEIGHT_TYPE: only EXPLICIT is supported");
    } else if (key.text == "EDGE_WEIGHT_FORMAT") {
      if (value.text != "FULL_MATRIX") return r.error(value.line, "EDGE_WEIGHT_FORMAT: only FULL_MATRIX is supported");
    } else if (key.text == "NAME" || key.text == "COMMENT") {
      // Free text to the end of the line.
      while (!r.done() && r.peek().line == value.line) r.next();
    } else {
      return r.error(key.line, fmt::format("unknown keyword '{}'", quote_for_message(key.text)));
    }
  }
  if (dimension < 0) return r.error(r.line(), "missing DIMENSION");
  if (!have_matrix) return r.error(r.line(), "missing EDGE_WEIGHT_SECTION");
  if (!have_windows) return r.error(r.line(), "missing TIME_WINDOW_SECTION");
  if (depot != 1) return r.error(r.line(), fmt::format("DEPOT_SECTION: the depot must be node 1, found {}", depot));

  const auto n = static_cast<std::size_t>(dimension);
  std::vector<Duration> travel(n * n);
  for (std::size_t k = 0; k < n * n; ++k) travel[k] = seconds(matrix[k]);
  auto oracle = MatrixTravel::create(n, std::move(travel));
  if (!oracle) return oracle.error().with_context(source);
  Problem p;
  p.travel = std::make_shared<MatrixTravel>(std::move(oracle).value());
  const Time origin{};
  p.robot.location = 0;
  p.robot.time = origin + seconds(windows[0].first);
  p.return_to = ReturnTo{0, origin + seconds(windows[0].second)};
  for (std::size_t k = 1; k < n; ++k) {
    ProblemTask t;
    t.id = std::to_string(k + 1);  // the file's node number
    t.release = origin + seconds(windows[k].first);
    t.deadline = origin + seconds(windows[k].second);
    t.deadline_on = DeadlineOn::kStart;
    t.start_location = t.end_location = k;
    p.tasks.push_back(std::move(t));
    p.location_names.push_back(std::to_string(k));
  }
  p.location_names.insert(p.location_names.begin(), "1");
  for (std::size_t k = 0; k < n; ++k) p.location_names[k] = std::to_string(k + 1);
  return p;
}

Result<Problem> load_tsptw(const std::filesystem::path& file) {
  auto text = read_text_file(file, kMaxTsptwBytes);
  if (!text) return text.error();
  return parse_tsptw(*text, printable_path(file));
}

}  // namespace rondo::schedule
