// One robot's route in the fleet solver, with what an insertion test needs precomputed (starts,
// ends, latest starts that keep the rest feasible, loads), and the insertion and removal of
// requests. Private to src/schedule.
//
// Insertion test: the inserted tasks and the tasks between them are timed one by one; from the
// first task after them on, a start no later than its stored latest start (static travel; the
// backward pass over travel, durations and the dock's deadline) proves the rest feasible in O(1),
// and a start equal to the stored one proves the rest unchanged. With time-dependent travel the
// rest is timed until the starts meet again.
#pragma once

#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "fleet_model.h"

namespace rondo::schedule::detail {

inline constexpr double kNoInsertion = std::numeric_limits<double>::infinity();
// The hierarchical objective's price of one more robot, in distance units: above any distance
// saving, below a drop (FleetCosts::drop_seconds).
inline constexpr double kVehicleCost = 1e6;

struct Tour {
  int robot = 0;
  std::vector<int> seq{};
  std::vector<std::int64_t> start{}, end{};
  std::vector<std::int64_t> latest{};          // latest start keeping the rest feasible (static travel)
  std::vector<std::int64_t> load_before{};     // on board when arriving at a position
  std::vector<std::int64_t> max_load_from{};   // largest load after serving any position >= k
  // Waiting before each start, summed from the first position (P), and P summed (Q, one longer):
  // a delay d at position k moves start j >= k by max(0, d - (P[j] - P[k])) with static travel,
  // so the sum of ends changes by a closed form over the positions it reaches (binary search).
  std::vector<std::int64_t> wait_sum{}, wait_sum_sum{};
  double distance = 0;
  double cost = 0;  // this route's part of the objective
  bool feasible = true;
  bool empty() const { return seq.empty(); }
};

struct Insertion {
  double delta = kNoInsertion;
  int route = -1;
  int pos = -1;       // the request's first task goes before seq[pos]
  int drop_pos = -1;  // its drop before seq[drop_pos] of the original route (>= pos), after the first
  bool found() const { return delta < kNoInsertion; }
};

class RouteOps {
 public:
  explicit RouteOps(const FleetModel& model) : m_(model) {}

  // Recomputes times, latest starts, loads, distance and cost from `seq`.
  void update(Tour& r) const;
  // The cheapest insertion of request `q` into route r (index `index`); positions are limited to
  // those the `after` links allow, given `route_of` (task -> route index, -1 unplanned). With
  // `blink` > 0, each position is skipped with that probability (SISR's blinks).
  // `open_cost`: what starting an empty route adds (the objective's own vehicle price, or 0).
  Insertion best_insertion(const Tour& r, int index, int q, const std::vector<int>& route_of, bool allow_empty,
                           double open_cost, double blink = 0, std::mt19937_64* rng = nullptr) const;
  void insert(Tour& r, const Insertion& ins, int q) const;
  // Removes the tasks of request q (they must be in r).
  void remove(Tour& r, int q) const;

 private:
  struct Walk {
    std::int64_t t = 0;      // when the robot is free
    std::size_t loc = 0;     // where it is
    std::int64_t load = 0;   // on board
    double delta = 0;        // change of the sum of ends and lateness so far (kSumOfEnds)
    std::int64_t start = 0;  // start of the last task timed
  };
  bool step_new(const Tour& r, int task, Walk& w) const;
  bool step_old(const Tour& r, int k, std::int64_t extra_load, Walk& w) const;
  bool finish(const Tour& r, int k, std::int64_t extra_load, Walk w, double& delta) const;
  double shifted_ends(const Tour& r, int k, std::int64_t delay) const;
  Walk walk_at(const Tour& r, int pos) const;
  double single_distance(const Tour& r, int pos, int task) const;
  double pair_distance(const Tour& r, int pos, int drop_pos, int a, int b) const;
  bool looks_clear(const Tour& r, int pos, int drop_pos, int look) const;
  std::pair<int, int> allowed_range(const Tour& r, int task, const std::vector<int>& route_of, int index) const;
  std::size_t prev_location(const Tour& r, int pos) const;
  std::int64_t dock_travel(const Tour& r, std::size_t from, std::int64_t depart) const;

  const FleetModel& m_;
};

}  // namespace rondo::schedule::detail
