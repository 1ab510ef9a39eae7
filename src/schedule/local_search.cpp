#include "local_search.h"

#include <algorithm>

namespace rondo::schedule::detail {

OrderImprover::OrderImprover(const Instance& instance, std::uint64_t seed)
    : in_(instance), rng_(seed), n_(instance.size()) {}

void OrderImprover::load(const std::vector<std::size_t>& order) {
  order_ = order;
  start_.assign(n_, 0);
  end_.assign(n_, 0);
  slack_.assign(n_, 0);
  retime(0);
}

void OrderImprover::retime(std::size_t from) {
  std::int64_t t = from == 0 ? 0 : end_[from - 1];
  std::size_t prev = from == 0 ? n_ : order_[from - 1];
  for (std::size_t k = from; k < n_; ++k) {
    const std::size_t x = order_[k];
    start_[k] = std::max(in_.release(x), t + in_.travel(prev, x, t));
    end_[k] = start_[k] + in_.duration(x);
    t = end_[k];
    prev = x;
  }
  objective_ = 0;
  for (std::size_t k = 0; k < n_; ++k) objective_ += end_[k];
  // Forward slack: how much the start at k may be delayed with every later task still in its
  // window and the return in time (exact for static travel).
  std::int64_t next = kNever;
  if (in_.has_return() && n_ > 0) next = in_.return_latest() - (t + in_.travel(prev, n_, t));
  for (std::size_t k = n_; k-- > 0;) {
    const std::size_t x = order_[k];
    std::int64_t s = std::min(in_.latest(x) - start_[k], next);
    slack_[k] = s;
    if (k > 0) {
      const std::int64_t arrival = end_[k - 1] + in_.travel(order_[k - 1], x, end_[k - 1]);
      next = std::min(kNever, s + (start_[k] - arrival));
    }
  }
}

bool OrderImprover::propagate(std::size_t q, std::int64_t t, std::size_t prev, std::int64_t& delta,
                              bool need_gain) const {
  // The forward slack counts only the expected starts; a chance constraint also bounds departures.
  const bool exact_slack = in_.static_travel() && !in_.has_window_travel();
  for (std::size_t k = q; k < n_; ++k) {
    const std::size_t x = order_[k];
    const std::int64_t s = std::max(in_.release(x), t + in_.travel(prev, x, t));
    if (!in_.window_allows(prev, x, t)) return false;
    if (s == start_[k]) return true;  // the old times resume from here
    const std::int64_t shift = s - start_[k];
    if (exact_slack && shift > slack_[k]) return false;
    if (s > in_.latest(x)) return false;
    delta += shift;
    // From here on every start is delayed by >= 0: no gain can come back.
    if (need_gain && shift > 0 && delta >= 0) return false;
    t = s + in_.duration(x);
    prev = x;
  }
  if (in_.has_return() && t + in_.travel(prev, n_, t) > in_.return_latest()) return false;
  return true;
}

bool OrderImprover::simulate(const std::size_t* tasks, std::size_t count, const std::int64_t* old_ends,
                             std::int64_t& t, std::size_t& prev, std::int64_t& delta) const {
  for (std::size_t c = 0; c < count; ++c) {
    const std::size_t x = tasks[c];
    const std::int64_t s = std::max(in_.release(x), t + in_.travel(prev, x, t));
    if (s > in_.latest(x) || !in_.window_allows(prev, x, t)) return false;
    t = s + in_.duration(x);
    delta += t - old_ends[c];
    prev = x;
  }
  return true;
}

bool OrderImprover::accept(std::vector<std::size_t> candidate) {
  if (!in_.order_respects_rules(candidate)) return false;
  std::size_t first = 0;
  while (first < n_ && candidate[first] == order_[first]) ++first;
  order_ = std::move(candidate);
  retime(first);
  return true;
}

// Moves order_[i, i+len) to after position p > i+len-1, scanning p upwards.
bool OrderImprover::try_forward(std::size_t i, std::size_t len, bool random_accept) {
  std::int64_t t = i == 0 ? 0 : end_[i - 1];
  std::size_t prev = i == 0 ? n_ : order_[i - 1];
  std::int64_t delta = 0;
  const std::size_t first = order_[i];
  std::vector<std::size_t> feasible_places;
  for (std::size_t p = i + len; p < n_; ++p) {
    // Shift old[p] left over the removed segment.
    const std::size_t x = order_[p];
    const std::int64_t s = std::max(in_.release(x), t + in_.travel(prev, x, t));
    if (s > in_.latest(x) || !in_.window_allows(prev, x, t)) break;  // guards odd oracles
    t = s + in_.duration(x);
    delta += t - end_[p];
    prev = x;
    // Insert the segment after old[p].
    const std::int64_t seg_start = std::max(in_.release(first), t + in_.travel(prev, first, t));
    if (seg_start > in_.latest(first) || !in_.window_allows(prev, first, t)) break;  // later places: later
    std::int64_t t2 = t, d2 = delta;
    std::size_t prev2 = prev;
    if (!simulate(&order_[i], len, &end_[i], t2, prev2, d2)) continue;
    if (!propagate(p + 1, t2, prev2, d2, !random_accept)) continue;
    if (random_accept) {
      feasible_places.push_back(p);
      continue;
    }
    if (d2 < 0) {
      std::vector<std::size_t> c(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(i));
      c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i + len),
               order_.begin() + static_cast<std::ptrdiff_t>(p + 1));
      c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i),
               order_.begin() + static_cast<std::ptrdiff_t>(i + len));
      c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(p + 1), order_.end());
      if (accept(std::move(c))) return true;
    }
  }
  if (random_accept && !feasible_places.empty()) {
    const std::size_t p = feasible_places[rng_() % feasible_places.size()];
    std::vector<std::size_t> c(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(i));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i + len),
             order_.begin() + static_cast<std::ptrdiff_t>(p + 1));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i),
             order_.begin() + static_cast<std::ptrdiff_t>(i + len));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(p + 1), order_.end());
    return accept(std::move(c));
  }
  return false;
}

// Moves order_[i, i+len) to before position p < i, scanning p downwards.
bool OrderImprover::try_backward(std::size_t i, std::size_t len, bool random_accept) {
  std::vector<std::size_t> piece;
  std::vector<std::int64_t> old_ends;
  std::vector<std::size_t> feasible_places;
  const std::size_t lowest = i > backward_reach_ ? i - backward_reach_ : 0;
  for (std::size_t p = i; p-- > lowest;) {
    // New order: old[0..p-1], segment, old[p..i-1], old[i+len..].
    piece.assign(order_.begin() + static_cast<std::ptrdiff_t>(i),
                 order_.begin() + static_cast<std::ptrdiff_t>(i + len));
    piece.insert(piece.end(), order_.begin() + static_cast<std::ptrdiff_t>(p),
                 order_.begin() + static_cast<std::ptrdiff_t>(i));
    old_ends.assign(end_.begin() + static_cast<std::ptrdiff_t>(i), end_.begin() + static_cast<std::ptrdiff_t>(i + len));
    old_ends.insert(old_ends.end(), end_.begin() + static_cast<std::ptrdiff_t>(p),
                    end_.begin() + static_cast<std::ptrdiff_t>(i));
    std::int64_t t = p == 0 ? 0 : end_[p - 1];
    std::size_t prev = p == 0 ? n_ : order_[p - 1];
    std::int64_t delta = 0;
    // The segment starts earlier the further back it goes; if its first task cannot start in
    // time here, it may still further back, so keep scanning.
    if (!simulate(piece.data(), piece.size(), old_ends.data(), t, prev, delta)) continue;
    if (!propagate(i + len, t, prev, delta, !random_accept)) continue;
    if (random_accept) {
      feasible_places.push_back(p);
      continue;
    }
    if (delta < 0) {
      std::vector<std::size_t> c(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(p));
      c.insert(c.end(), piece.begin(), piece.end());
      c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i + len), order_.end());
      if (accept(std::move(c))) return true;
    }
  }
  if (random_accept && !feasible_places.empty()) {
    const std::size_t p = feasible_places[rng_() % feasible_places.size()];
    std::vector<std::size_t> c(order_.begin(), order_.begin() + static_cast<std::ptrdiff_t>(p));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i),
             order_.begin() + static_cast<std::ptrdiff_t>(i + len));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(p),
             order_.begin() + static_cast<std::ptrdiff_t>(i));
    c.insert(c.end(), order_.begin() + static_cast<std::ptrdiff_t>(i + len), order_.end());
    return accept(std::move(c));
  }
  return false;
}

std::int64_t OrderImprover::descend(std::vector<std::size_t>& order, const StopCondition& stop) {
  load(order);
  bool improved = true;
  while (improved) {
    improved = false;
    for (std::size_t len = 1; len <= 3; ++len) {
      for (std::size_t i = 0; i + len <= n_; ++i) {
        if (stop.should_stop()) {
          order = order_;
          return objective_;
        }
        const std::int64_t before = objective_;
        if (try_forward(i, len, false) || try_backward(i, len, false)) {
          if (objective_ < before) improved = true;
        }
      }
    }
  }
  order = order_;
  return objective_;
}

bool OrderImprover::perturb_once() {
  if (n_ < 2) return false;
  for (int attempt = 0; attempt < 20; ++attempt) {
    const std::size_t len = 1 + rng_() % std::min<std::size_t>(3, n_ - 1);
    const std::size_t i = rng_() % (n_ - len + 1);
    if ((rng_() & 1U) ? try_forward(i, len, true) : try_backward(i, len, true)) return true;
  }
  return false;
}

std::int64_t OrderImprover::iterate(std::vector<std::size_t>& best, const StopCondition& stop,
                                    std::int64_t max_rounds) {
  std::int64_t best_objective = descend(best, stop);
  std::vector<std::size_t> current = best;
  std::int64_t current_objective = best_objective;
  std::int64_t since_best = 0;
  for (std::int64_t round = 0; round < max_rounds && !stop.should_stop(); ++round) {
    load(current);
    const std::size_t kicks = 1 + rng_() % 3;
    for (std::size_t k = 0; k < kicks; ++k) perturb_once();
    std::vector<std::size_t> candidate = order_;
    const std::int64_t obj = descend(candidate, stop);
    if (obj < best_objective) {
      best = candidate;
      best_objective = obj;
      since_best = 0;
    } else {
      ++since_best;
    }
    // Accept sideways and slightly worse moves; return to the best after a long drought.
    if (obj <= current_objective + current_objective / 2000) {
      current = std::move(candidate);
      current_objective = obj;
    }
    if (since_best > 0 && since_best % 50 == 0) {
      current = best;
      current_objective = best_objective;
    }
  }
  return best_objective;
}

}  // namespace rondo::schedule::detail
