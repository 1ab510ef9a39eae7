#include "rondo/lang/words.h"

#include <algorithm>
#include <array>
#include <numeric>

namespace rondo::lang {
namespace {

constexpr std::array<std::string_view, 5> kFiller = {"the", "a", "an", "room", "office"};

bool is_filler(std::string_view word) {
  return std::find(kFiller.begin(), kFiller.end(), word) != kFiller.end();
}

bool is_edge_punctuation(char c) {
  return c == ',' || c == '.' || c == ';' || c == ':' || c == '!' || c == '?' || c == '"' || c == '(' || c == ')' ||
         c == '[' || c == ']';
}

// Lower case, U+2018/U+2019 as ', and every whitespace byte as a space.
std::string fold(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\xE2' && i + 2 < text.size() && text[i + 1] == '\x80' &&
        (text[i + 2] == '\x98' || text[i + 2] == '\x99')) {
      out.push_back('\'');
      i += 2;
    } else if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
      out.push_back(' ');
    } else if (c >= 'A' && c <= 'Z') {
      out.push_back(static_cast<char>(c - 'A' + 'a'));
    } else {
      out.push_back(c);
    }
  }
  return out;
}

std::vector<std::string> words_of(const std::string& folded) {
  std::vector<std::string> words;
  std::size_t i = 0;
  while (i < folded.size()) {
    while (i < folded.size() && folded[i] == ' ') ++i;
    std::size_t j = i;
    while (j < folded.size() && folded[j] != ' ') ++j;
    std::size_t b = i;
    std::size_t e = j;
    while (b < e && is_edge_punctuation(folded[b])) ++b;
    while (e > b && is_edge_punctuation(folded[e - 1])) --e;
    if (e > b) words.emplace_back(folded.substr(b, e - b));
    i = j;
  }
  return words;
}

std::string join(const std::vector<std::string>& words, bool skip_filler) {
  std::string out;
  for (const auto& w : words) {
    if (skip_filler && is_filler(w)) continue;
    if (!out.empty()) out.push_back(' ');
    out += w;
  }
  return out;
}

}  // namespace

std::string normalise_phrase(std::string_view text) {
  const auto words = words_of(fold(text));
  std::string out = join(words, true);
  return out.empty() ? join(words, false) : out;
}

std::string normalise_object(std::string_view text) {
  auto words = words_of(fold(text));
  std::size_t b = 0;
  while (b < words.size() && (words[b] == "the" || words[b] == "a" || words[b] == "an")) ++b;
  words.erase(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(b));
  return join(words, false);
}

std::string slug(std::string_view text) {
  std::string out;
  bool dash = false;
  for (char c : text) {
    const bool alnum = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || (c >= 'A' && c <= 'Z');
    if (alnum) {
      if (dash && !out.empty()) out.push_back('-');
      dash = false;
      out.push_back(c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c);
    } else {
      dash = true;
    }
  }
  return out.empty() ? "x" : out;
}

std::size_t edit_distance(std::string_view a, std::string_view b, std::size_t cap) {
  if (a.size() > cap + b.size() || b.size() > cap + a.size()) return cap;
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    std::size_t best = row[0];
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
      best = std::min(best, row[j]);
    }
    if (best >= cap) return cap;
  }
  return std::min(row[b.size()], cap);
}

std::vector<std::string> nearest(std::string_view word, const std::vector<std::string>& candidates, std::size_t count) {
  const auto parts_of = [](std::string_view s) {
    std::vector<std::string_view> parts;
    std::size_t b = 0;
    for (std::size_t i = 0; i <= s.size(); ++i) {
      if (i == s.size() || s[i] == ' ' || s[i] == '-') {
        if (i > b) parts.push_back(s.substr(b, i - b));
        b = i + 1;
      }
    }
    return parts;
  };
  const auto mine = parts_of(word);
  struct Rank {
    std::size_t shared;  // words (split at spaces and '-') in common with `word`: more ranks first
    std::size_t distance;
    std::size_t prefix;  // length of the prefix shared with `word`: longer ranks first on a tie
    std::size_t index;
  };
  std::vector<Rank> ranked;
  ranked.reserve(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const std::string& c = candidates[i];
    std::size_t p = 0;
    while (p < c.size() && p < word.size() && c[p] == word[p]) ++p;
    std::size_t shared = 0;
    for (const auto& part : parts_of(c)) shared += std::find(mine.begin(), mine.end(), part) != mine.end() ? 1u : 0u;
    ranked.push_back({shared, edit_distance(word, c), p, i});
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const Rank& x, const Rank& y) {
    if (x.shared != y.shared) return x.shared > y.shared;
    return x.distance != y.distance ? x.distance < y.distance : x.prefix > y.prefix;
  });
  std::vector<std::string> out;
  for (std::size_t k = 0; k < ranked.size() && out.size() < count; ++k) {
    const std::string& c = candidates[ranked[k].index];
    if (std::find(out.begin(), out.end(), c) == out.end()) out.push_back(c);
  }
  return out;
}

}  // namespace rondo::lang
