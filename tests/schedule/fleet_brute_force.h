// A slow, obviously correct fleet scheduler for tests: tries every way of giving each robot an
// ordered list of tasks (the rest dropped), times each route exactly as the rules say, and keeps
// the cheapest plan under the problem's objective. Prunes only prefixes that already break a rule
// or already cost at least the best plan. Up to 3 robots and ~8 tasks.
#pragma once

#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "rondo/schedule/fleet_problem.h"

namespace rondo::schedule::testing {

// Lexicographic cost: (drop cost, vehicles, distance) for kVehiclesThenDistance; (drop cost + sum
// of ends + lateness, 0, 0) for kSumOfEnds.
struct FleetCost {
  double first = 0;
  double vehicles = 0;
  double rest = 0;
  bool operator<(const FleetCost& o) const {
    auto key = [](const FleetCost& c) { return std::tuple(c.first, c.vehicles, c.rest); };
    return key(*this) < key(o);
  }
};

class FleetBruteForce {
 public:
  explicit FleetBruteForce(const FleetProblem& p) : p_(p), n_(p.tasks.size()), used_(n_, false), robot_of_(n_, -1) {}

  std::optional<FleetCost> solve() {
    start_robot(0, {});
    return best_;
  }

 private:
  struct State {
    Time now{};
    LocationIndex here = 0;
    std::int64_t load = 0;
    std::map<std::string, int> looks{};
    std::vector<std::string> jobs{};
    Time end_of_last{};
  };
  bool hierarchical() const { return p_.objective == FleetObjective::kVehiclesThenDistance; }

  void start_robot(std::size_t r, FleetCost cost) {
    if (r == p_.robots.size()) {
      for (std::size_t i = 0; i < n_; ++i)
        if (!used_[i]) cost.first += p_.costs.drop_seconds * (1 + p_.tasks[i].task.priority);
      // `after`: a planned task's predecessors are planned (same robot, earlier: checked on the way).
      for (std::size_t i = 0; i < n_; ++i)
        for (std::size_t a : p_.tasks[i].task.after)
          if (used_[i] && !used_[a]) return;
      if (!best_ || cost < *best_) best_ = cost;
      return;
    }
    State s{.now = p_.robots[r].free_from, .here = p_.robots[r].location};
    extend(r, s, cost, 0);
  }

  void extend(std::size_t r, State& s, FleetCost cost, std::size_t count) {
    if (best_ && !(cost < *best_)) return;  // every part only grows
    // Close this robot's route.
    if (s.jobs.empty()) {
      FleetCost closed = cost;
      bool ok = true;
      if (count > 0) {
        const FleetRobot& robot = p_.robots[r];
        if (robot.end) {
          ok = s.now + robot_travel(p_, r, s.here, robot.end->location, s.now) <= robot.end->deadline;
          closed.rest += hierarchical() ? p_.distance_between(s.here, robot.end->location) : 0;
        }
        if (hierarchical()) closed.vehicles += 1;
      }
      if (ok) start_robot(r + 1, closed);
    }
    for (std::size_t i = 0; i < n_; ++i) {
      if (used_[i]) continue;
      const FleetTask& f = p_.tasks[i];
      const ProblemTask& t = f.task;
      const FleetRobot& robot = p_.robots[r];
      if (f.pinned_robot && *f.pinned_robot != r) continue;
      if (!f.action.empty() && std::find(robot.actions.begin(), robot.actions.end(), f.action) == robot.actions.end())
        continue;
      bool ready = true;
      for (std::size_t a : t.after) ready = ready && used_[a] && robot_of_[a] == static_cast<long>(r);
      for (std::size_t k = 0; k < n_; ++k)  // `after` links to a later task planned elsewhere
        for (std::size_t a : p_.tasks[k].task.after)
          if (a == i && used_[k]) ready = false;
      if (!ready) continue;
      State next = s;
      const Time arrival = s.now + robot_travel(p_, r, s.here, t.start_location, s.now);
      const Time start = std::max(arrival, t.release);
      if (start > t.latest_start()) continue;
      const Time end = start + t.duration;
      next.load += f.demand;
      if (t.transfer) {
        const ItemTransfer& x = *t.transfer;
        if (x.action == ItemAction::kPickup) {
          next.load += x.load;
          if (!x.appearance.empty() && next.looks[x.appearance]++ > 0) continue;
          next.jobs.push_back(x.job);
        } else {
          auto it = std::find(next.jobs.begin(), next.jobs.end(), x.job);
          if (it == next.jobs.end()) continue;
          next.jobs.erase(it);
          next.load -= x.load;
          if (!x.appearance.empty()) next.looks[x.appearance]--;
        }
      }
      if (robot.capacity > 0 && next.load > robot.capacity) continue;
      FleetCost c = cost;
      if (hierarchical()) {
        c.rest += p_.distance_between(s.here, t.start_location);
      } else {
        c.first += to_seconds(end - robot.free_from);
        if (f.due && end > *f.due) c.first += p_.costs.lateness_per_second * to_seconds(end - *f.due) * (1 + t.priority);
      }
      next.now = end;
      next.here = t.end_location;
      used_[i] = true;
      robot_of_[i] = static_cast<long>(r);
      extend(r, next, c, count + 1);
      used_[i] = false;
      robot_of_[i] = -1;
    }
  }

  const FleetProblem& p_;
  std::size_t n_;
  std::vector<bool> used_;
  std::vector<long> robot_of_;
  std::optional<FleetCost> best_;
};

}  // namespace rondo::schedule::testing
