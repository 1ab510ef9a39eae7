// The solvers' compiled view of a Problem: times as int64 milliseconds from robot.time, tasks as
// 0..n-1, node n standing for the robot's start (as a "from") and the return (as a "to"), a cached
// travel matrix when the oracle is static, lower bounds, and the item/precedence rules as data.
// Private to src/schedule.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rondo/schedule/problem.h"
#include "rondo/schedule/schedule.h"

namespace rondo::schedule::detail {

inline constexpr std::int64_t kNever = INT64_MAX / 4;

class Instance {
 public:
  explicit Instance(const Problem& problem);

  std::size_t size() const { return n_; }
  const Problem& problem() const { return *problem_; }
  std::int64_t release(std::size_t i) const { return release_[i]; }
  std::int64_t latest(std::size_t i) const { return latest_[i]; }
  std::int64_t duration(std::size_t i) const { return duration_[i]; }
  bool static_travel() const { return static_; }
  bool has_return() const { return has_return_; }
  std::int64_t return_latest() const { return return_latest_; }
  // Travel from the end of `from` (n = robot start) to the start of `to` (n = the return; zero when
  // there is none), leaving at `depart`.
  std::int64_t travel(std::size_t from, std::size_t to, std::int64_t depart) const {
    if (static_) return arc_[from * (n_ + 1) + to];
    return travel_dynamic(from, to, depart);
  }
  // The chance constraint (Problem::window_travel): may `to` start in its window after leaving
  // `from` at `depart`, allowing for the window travel? Always true without one. The expected
  // start's own check (start <= latest) is separate.
  bool has_window_travel() const { return window_; }
  bool window_allows(std::size_t from, std::size_t to, std::int64_t depart) const {
    if (!window_ || to == n_) return true;
    const std::int64_t need = static_ ? window_arc_[from * (n_ + 1) + to] : window_travel_dynamic(from, to, depart);
    return depart + need <= latest_[to];
  }
  // Lower bound on the time from the end of `from` to the arrival at the start of `to`, over any
  // sequence of tasks in between (shortest paths over lower-bound travel plus durations).
  std::int64_t min_gap(std::size_t from, std::size_t to) const { return gap_[from * (n_ + 1) + to]; }
  // Largest min_gap out of `from` to any task.
  std::int64_t max_gap_from(std::size_t from) const { return max_gap_[from]; }
  // Tasks by increasing latest start.
  const std::vector<std::size_t>& by_latest() const { return by_latest_; }
  // Tasks by increasing release + duration.
  const std::vector<std::size_t>& by_earliest_end() const { return by_earliest_end_; }
  std::int64_t min_step() const { return min_step_; }

  // Items and precedence.
  bool has_rules() const { return has_rules_; }
  const std::vector<std::size_t>& predecessors(std::size_t i) const { return preds_[i]; }
  std::int64_t load_delta(std::size_t i) const { return load_delta_[i]; }
  std::int64_t initial_load() const { return initial_load_; }
  std::int64_t capacity() const { return capacity_; }
  // May task j run next, given the set of tasks done (`done(i)` answers for any task) and the
  // current load? Checks predecessors, capacity and same-looking items.
  template <class Done>
  bool allows(std::size_t j, std::int64_t load, const Done& done) const {
    for (std::size_t a : preds_[j])
      if (!done(a)) return false;
    if (load_delta_[j] > 0) {
      if (capacity_ > 0 && load + load_delta_[j] > capacity_) return false;
      for (const Holder& h : look_alikes_[j]) {
        const bool picked = h.pickup == kNone || done(h.pickup);
        const bool dropped = h.drop != kNone && done(h.drop);
        if (picked && !dropped) return false;
      }
    }
    return true;
  }
  // The whole order against the item and precedence rules (not times).
  bool order_respects_rules(const std::vector<std::size_t>& order) const;

  // Converts relative times back: a Schedule from an order, exact (uses the oracle). Precondition:
  // the order is feasible.
  Schedule to_schedule(const std::vector<std::size_t>& order, SolveStatus status) const;
  // Relative end time of the order and its objective, or nothing when infeasible (times only).
  struct Timing {
    bool feasible = false;
    std::int64_t objective = 0;
  };
  Timing time(const std::vector<std::size_t>& order) const;

 private:
  static constexpr std::size_t kNone = SIZE_MAX;
  struct Holder {
    std::size_t pickup;  // kNone: on board from the start
    std::size_t drop;    // kNone: never dropped
  };
  std::int64_t travel_dynamic(std::size_t from, std::size_t to, std::int64_t depart) const;
  std::int64_t window_travel_dynamic(std::size_t from, std::size_t to, std::int64_t depart) const;
  LocationIndex from_location(std::size_t from) const;
  LocationIndex to_location(std::size_t to) const;

  const Problem* problem_;
  std::size_t n_;
  bool static_ = true;
  bool window_ = false;  // a chance constraint
  bool has_return_ = false;
  std::int64_t return_latest_ = kNever;
  std::vector<std::int64_t> release_, latest_, duration_;
  std::vector<std::int64_t> arc_, window_arc_, gap_, max_gap_;
  std::vector<std::size_t> by_latest_, by_earliest_end_;
  std::int64_t min_step_ = 0;
  bool has_rules_ = false;
  std::vector<std::vector<std::size_t>> preds_;
  std::vector<std::int64_t> load_delta_;
  std::int64_t initial_load_ = 0;
  std::int64_t capacity_ = 0;
  std::vector<std::vector<Holder>> look_alikes_;  // per pickup task: the other items that look alike
};

}  // namespace rondo::schedule::detail
