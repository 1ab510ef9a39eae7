#include "label_dp.h"

#include <algorithm>
#include <cstring>

namespace rondo::schedule::detail {

namespace {

constexpr std::uint32_t kEmpty = UINT32_MAX;
constexpr std::int64_t kExtensionsPerPoll = 256;

std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The labels of one stage, structure of arrays; masks are `words` 64-bit words per label.
struct Stage {
  std::size_t words = 1;
  std::vector<std::uint64_t> masks;
  std::vector<std::uint32_t> last;
  std::vector<std::int64_t> end, cost, load, score;
  std::vector<std::uint32_t> history;  // index into the global (parent, last) history
  std::vector<std::uint32_t> next_same;  // next label on the same state
  std::vector<char> alive;

  std::size_t size() const { return last.size(); }
  const std::uint64_t* mask(std::size_t i) const { return masks.data() + i * words; }
  void clear() {
    masks.clear(); last.clear(); end.clear(); cost.clear(); load.clear(); score.clear();
    history.clear(); next_same.clear(); alive.clear();
  }
};

bool has(const std::uint64_t* mask, std::size_t j) { return (mask[j >> 6] >> (j & 63)) & 1U; }

// Open addressing from state to the first label of that state in the next stage.
class StateTable {
 public:
  void reset(std::size_t expected) {
    std::size_t cap = 64;
    while (cap < expected * 2) cap <<= 1;
    slots_.assign(cap, kEmpty);
    used_ = 0;
  }
  // Returns the slot for (mask, last); *found says whether it holds a label of that state.
  std::size_t find(const Stage& s, const std::uint64_t* mask, std::uint32_t last, bool* found) const {
    std::uint64_t h = mix(last);
    for (std::size_t w = 0; w < s.words; ++w) h = mix(h ^ mask[w]);
    std::size_t i = static_cast<std::size_t>(h) & (slots_.size() - 1);
    while (slots_[i] != kEmpty) {
      const std::uint32_t l = slots_[i];
      if (s.last[l] == last && std::memcmp(s.mask(l), mask, s.words * 8) == 0) {
        *found = true;
        return i;
      }
      i = (i + 1) & (slots_.size() - 1);
    }
    *found = false;
    return i;
  }
  std::uint32_t at(std::size_t slot) const { return slots_[slot]; }
  void set(std::size_t slot, std::uint32_t label) {
    if (slots_[slot] == kEmpty) ++used_;
    slots_[slot] = label;
  }
  bool crowded() const { return used_ * 2 > slots_.size(); }
  void rehash(const Stage& s) {
    std::vector<std::uint32_t> old;
    old.swap(slots_);
    slots_.assign(old.size() * 2, kEmpty);
    used_ = 0;
    for (std::uint32_t l : old) {
      if (l == kEmpty) continue;
      bool found = false;
      set(find(s, s.mask(l), s.last[l], &found), l);
    }
  }

 private:
  std::vector<std::uint32_t> slots_;
  std::size_t used_ = 0;
};

}  // namespace

LabelDpResult run_label_dp(const Instance& in, const LabelDpOptions& opt, const StopCondition& stop) {
  LabelDpResult result;
  const std::size_t n = in.size();
  const bool exact = opt.beam_width == 0;
  const bool rules = in.has_rules();
  if (n == 0) {
    if (in.has_return() && in.travel(n, n, 0) > in.return_latest()) {
      result.outcome = LabelDpResult::Outcome::kNoneFound;
    } else {
      result.outcome = 0 < opt.upper_bound ? LabelDpResult::Outcome::kFound : LabelDpResult::Outcome::kNoneFound;
      result.objective = 0;
    }
    result.exhaustive = true;
    return result;
  }
  const std::size_t words = (n + 63) / 64;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> history;  // (parent history, task)
  history.push_back({kEmpty, static_cast<std::uint32_t>(n)});

  Stage cur, nxt;
  cur.words = nxt.words = words;
  cur.masks.assign(words, 0);
  cur.last.push_back(static_cast<std::uint32_t>(n));
  cur.end.push_back(0);
  cur.cost.push_back(0);
  cur.load.push_back(in.initial_load());
  cur.score.push_back(0);
  cur.history.push_back(0);
  cur.next_same.push_back(kEmpty);
  cur.alive.push_back(1);

  StateTable table;
  std::vector<std::uint64_t> mask(words);
  std::vector<std::size_t> keep;
  std::int64_t polls = 0;  // extensions tried since the last poll
  bool beam_cut = false;
  const auto& by_latest = in.by_latest();
  const auto& by_early = in.by_earliest_end();

  for (std::size_t stage = 1; stage <= n; ++stage) {
    nxt.clear();
    table.reset(std::min<std::size_t>(cur.size() * 4, 1U << 22));
    const std::size_t remaining_after = n - stage;
    for (std::size_t l = 0; l < cur.size(); ++l) {
      if (!cur.alive[l]) continue;
      // A poll per ~256 extensions tried, about the work of one local-search move, so that a poll
      // budget (PollBudgetStop) buys similar time in every phase and at every problem size.
      polls += static_cast<std::int64_t>(remaining_after + 1);
      if (polls >= kExtensionsPerPoll) {
        polls = 0;
        if (stop.should_stop()) return result;  // kAborted
      }
      const std::uint64_t* m = cur.mask(l);
      const std::size_t i = cur.last[l];
      const std::int64_t t = cur.end[l];
      auto done = [m](std::size_t k) { return has(m, k); };
      // Tasks are mostly done in order of latest start: skip the done prefix once per label.
      std::size_t first_open = 0;
      while (first_open < n && has(m, by_latest[first_open])) ++first_open;
      for (std::size_t j = 0; j < n; ++j) {
        if (has(m, j)) continue;
        const std::int64_t start = std::max(in.release(j), t + in.travel(i, j, t));
        if (start > in.latest(j) || !in.window_allows(i, j, t)) continue;
        if (rules && !in.allows(j, cur.load[l], done)) continue;
        const std::int64_t e = start + in.duration(j);
        const std::int64_t c = cur.cost[l] + e;
        if (c >= opt.upper_bound) continue;
        // Window elimination: every other task still to do must stay reachable from j.
        bool dead = false;
        const std::int64_t horizon = e + in.max_gap_from(j);
        for (std::size_t q = first_open; q < n; ++q) {
          const std::size_t k = by_latest[q];
          if (in.latest(k) >= horizon) break;
          if (k == j || has(m, k)) continue;
          if (e + in.min_gap(j, k) > in.latest(k)) {
            dead = true;
            break;
          }
        }
        if (dead) continue;
        if (in.has_return() && e + in.min_gap(j, n) > in.return_latest()) continue;
        std::int64_t score = c;
        if (exact) {
          // Two lower bounds on the sum of the remaining end times; take the larger.
          std::int64_t lb1 = 0, lb2 = 0, rank = 0;
          for (std::size_t k = 0; k < n; ++k) {
            if (k == j || has(m, k)) continue;
            lb1 += std::max(in.release(k), e + in.min_gap(j, k)) + in.duration(k);
          }
          for (std::size_t k : by_early) {
            if (k == j || has(m, k)) continue;
            ++rank;
            lb2 += std::max(in.release(k) + in.duration(k), e + rank * in.min_step());
          }
          score = c + std::max(lb1, lb2);
          if (score >= opt.upper_bound) continue;
        } else {
          score = c + static_cast<std::int64_t>(remaining_after) * e;
        }
        std::memcpy(mask.data(), m, words * 8);
        mask[j >> 6] |= std::uint64_t{1} << (j & 63);
        bool found = false;
        const std::size_t slot = table.find(nxt, mask.data(), static_cast<std::uint32_t>(j), &found);
        if (found) {
          bool dominated = false;
          for (std::uint32_t o = table.at(slot); o != kEmpty; o = nxt.next_same[o]) {
            if (!nxt.alive[o]) continue;
            if (nxt.end[o] <= e && nxt.cost[o] <= c) {
              dominated = true;
              break;
            }
            if (e <= nxt.end[o] && c <= nxt.cost[o]) nxt.alive[o] = 0;
          }
          if (dominated) continue;
        }
        const auto id = static_cast<std::uint32_t>(nxt.size());
        nxt.masks.insert(nxt.masks.end(), mask.begin(), mask.end());
        nxt.last.push_back(static_cast<std::uint32_t>(j));
        nxt.end.push_back(e);
        nxt.cost.push_back(c);
        nxt.load.push_back(cur.load[l] + in.load_delta(j));
        nxt.score.push_back(score);
        nxt.history.push_back(cur.history[l]);  // parent's history entry, replaced on survival
        nxt.next_same.push_back(found ? table.at(slot) : kEmpty);
        nxt.alive.push_back(1);
        table.set(slot, id);
        if (table.crowded()) table.rehash(nxt);
        if (exact && nxt.size() > opt.max_labels_per_stage) return result;  // kAborted
      }
    }
    // Survivors: all alive labels (exact) or the best beam_width by score.
    keep.clear();
    for (std::size_t l = 0; l < nxt.size(); ++l)
      if (nxt.alive[l]) keep.push_back(l);
    if (!exact && keep.size() > opt.beam_width) {
      std::nth_element(keep.begin(), keep.begin() + static_cast<std::ptrdiff_t>(opt.beam_width), keep.end(),
                       [&](std::size_t a, std::size_t b) { return nxt.score[a] < nxt.score[b]; });
      keep.resize(opt.beam_width);
      beam_cut = true;
    }
    result.labels += keep.size();
    if (keep.empty()) {
      result.outcome = LabelDpResult::Outcome::kNoneFound;
      result.exhaustive = exact;
      return result;
    }
    // Compact the survivors into `cur` and record their history.
    cur.clear();
    for (std::size_t l : keep) {
      history.push_back({nxt.history[l], nxt.last[l]});
      cur.masks.insert(cur.masks.end(), nxt.mask(l), nxt.mask(l) + words);
      cur.last.push_back(nxt.last[l]);
      cur.end.push_back(nxt.end[l]);
      cur.cost.push_back(nxt.cost[l]);
      cur.load.push_back(nxt.load[l]);
      cur.score.push_back(nxt.score[l]);
      cur.history.push_back(static_cast<std::uint32_t>(history.size() - 1));
      cur.next_same.push_back(kEmpty);
      cur.alive.push_back(1);
    }
    if (history.size() > opt.max_labels_total) return result;  // kAborted: memory budget
  }
  // Complete sequences: check the return and pick the cheapest.
  std::size_t best = kEmpty;
  for (std::size_t l = 0; l < cur.size(); ++l) {
    const std::int64_t t = cur.end[l];
    if (in.has_return() && t + in.travel(cur.last[l], n, t) > in.return_latest()) continue;
    if (cur.cost[l] >= opt.upper_bound) continue;
    if (best == kEmpty || cur.cost[l] < cur.cost[best]) best = l;
  }
  result.exhaustive = exact && !beam_cut;
  if (best == kEmpty) {
    result.outcome = LabelDpResult::Outcome::kNoneFound;
    return result;
  }
  result.outcome = LabelDpResult::Outcome::kFound;
  result.objective = cur.cost[best];
  for (std::uint32_t h = cur.history[best]; h != 0; h = history[h].first) result.order.push_back(history[h].second);
  std::reverse(result.order.begin(), result.order.end());
  return result;
}

}  // namespace rondo::schedule::detail
