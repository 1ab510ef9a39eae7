#include "tokens.h"

#include <array>
#include <charconv>

#include "rondo/lang/words.h"

namespace rondo::lang::detail {
namespace {

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}

bool is_edge_punctuation(char c) {
  return c == ',' || c == '.' || c == ';' || c == ':' || c == '!' || c == '?' || c == '"' || c == '(' || c == ')' ||
         c == '[' || c == ']';
}

std::optional<int> digits(std::string_view s) {
  if (s.empty() || s.size() > 4) return std::nullopt;
  int v = 0;
  auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace

Tokens tokenize(std::string_view sentence) {
  Tokens out;
  std::size_t i = 0;
  while (i < sentence.size()) {
    while (i < sentence.size() && is_space(sentence[i])) ++i;
    std::size_t j = i;
    while (j < sentence.size() && !is_space(sentence[j])) ++j;
    std::size_t b = i;
    std::size_t e = j;
    while (b < e && is_edge_punctuation(sentence[b])) ++b;
    while (e > b && is_edge_punctuation(sentence[e - 1])) --e;
    if (e > b) {
      Token t{std::string(sentence.substr(b, e - b)), {}, sentence.substr(e, j - e).find(',') != std::string_view::npos};
      t.word = normalise_phrase(t.text);  // one word: folding only (a lone filler word keeps itself)
      out.push_back(std::move(t));
    }
    i = j;
  }
  return out;
}

std::string text_of(const Tokens& t, std::size_t begin, std::size_t end) {
  std::string out;
  for (std::size_t i = begin; i < end && i < t.size(); ++i) {
    if (!out.empty()) out.push_back(' ');
    out += t[i].text;
  }
  return out;
}

std::optional<Duration> clock_time(std::string_view word) {
  if (word == "noon" || word == "midday") return hours(12);
  std::string_view s = word;
  int add = -1;  // -1: 24-hour clock; 0: am; 12: pm
  if (s.size() > 2 && (s.ends_with("am") || s.ends_with("pm"))) {
    add = s.ends_with("pm") ? 12 : 0;
    s.remove_suffix(2);
  }
  int h = 0;
  int m = 0;
  if (const auto colon = s.find(':'); colon != std::string_view::npos) {
    const auto hh = digits(s.substr(0, colon));
    const auto mm = s.substr(colon + 1);
    const auto mv = mm.size() == 2 ? digits(mm) : std::nullopt;
    if (!hh || !mv || s.substr(0, colon).size() > 2) return std::nullopt;
    h = *hh;
    m = *mv;
  } else {
    if (add < 0) return std::nullopt;  // "15" alone is a number, not a time
    const auto hh = digits(s);
    if (!hh || s.size() > 2) return std::nullopt;
    h = *hh;
  }
  if (m > 59) return std::nullopt;
  if (add >= 0) {
    if (h < 1 || h > 12) return std::nullopt;
    h = h % 12 + add;
  } else if (h > 24 || (h == 24 && m != 0)) {
    return std::nullopt;
  }
  return hours(h) + minutes(m);
}

std::optional<std::chrono::weekday> weekday_named(std::string_view word) {
  static constexpr std::array<std::string_view, 7> kNames = {"sunday",   "monday", "tuesday", "wednesday",
                                                             "thursday", "friday", "saturday"};
  std::string_view w = word;
  if (w.size() > 3 && w.ends_with('s')) w.remove_suffix(1);
  for (unsigned d = 0; d < kNames.size(); ++d) {
    if (w == kNames[d] || w == kNames[d].substr(0, 3)) return std::chrono::weekday{d};
  }
  return std::nullopt;
}

std::optional<int> count_of(std::string_view word) {
  static constexpr std::array<std::string_view, 13> kNames = {
      "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine", "ten", "eleven", "twelve"};
  for (int n = 0; n < static_cast<int>(kNames.size()); ++n) {
    if (word == kNames[static_cast<std::size_t>(n)]) return n;
  }
  return digits(word);
}

std::optional<Duration> unit_of(std::string_view word) {
  if (word == "minute" || word == "minutes" || word == "min" || word == "mins") return minutes(1);
  if (word == "hour" || word == "hours" || word == "h" || word == "hr" || word == "hrs") return hours(1);
  return std::nullopt;
}

}  // namespace rondo::lang::detail
