// A slow, obviously correct scheduler for tests: tries every order (depth first), times each
// prefix exactly as the rules say (the chance constraint's window travel included), and keeps the cheapest complete order. Its only pruning:
// a prefix that already breaks a rule, or already costs at least the best complete order (costs
// only grow), is not extended. Up to ~12 tasks.
#pragma once

#include <map>
#include <optional>
#include <vector>

#include "rondo/schedule/problem.h"

namespace rondo::schedule::testing {

struct BruteForceAnswer {
  std::optional<Duration> objective;  // nothing: no order holds every task
  std::vector<std::size_t> order;
};

inline BruteForceAnswer brute_force(const Problem& p) {
  const std::size_t n = p.tasks.size();
  BruteForceAnswer best;
  std::vector<std::size_t> order;
  std::vector<bool> used(n, false);
  std::map<std::string, int> looks;
  for (const auto& item : p.robot.on_board)
    if (!item.appearance.empty()) looks[item.appearance]++;
  std::int64_t load = 0;
  for (const auto& item : p.robot.on_board) load += item.load;

  auto extend = [&](auto&& self, Time now, LocationIndex here, Duration cost) -> void {
    if (best.objective && cost >= *best.objective) return;
    if (order.size() == n) {
      if (p.return_to && now + p.travel->travel(here, p.return_to->location, now) > p.return_to->deadline) return;
      best.objective = cost;
      best.order = order;
      return;
    }
    for (std::size_t j = 0; j < n; ++j) {
      if (used[j]) continue;
      const ProblemTask& t = p.tasks[j];
      bool ready = true;
      for (std::size_t a : t.after) ready = ready && used[a];
      // A drop needs its pickup done (when the job has a pickup task).
      if (t.transfer && t.transfer->action == ItemAction::kDrop)
        for (std::size_t k = 0; k < n; ++k)
          if (p.tasks[k].transfer && p.tasks[k].transfer->job == t.transfer->job &&
              p.tasks[k].transfer->action == ItemAction::kPickup && !used[k])
            ready = false;
      if (!ready) continue;
      const bool pickup = t.transfer && t.transfer->action == ItemAction::kPickup;
      const bool drop = t.transfer && t.transfer->action == ItemAction::kDrop;
      if (pickup && p.robot.capacity > 0 && load + t.transfer->load > p.robot.capacity) continue;
      if (pickup && !t.transfer->appearance.empty() && looks[t.transfer->appearance] > 0) continue;
      const Time start = std::max(now + p.travel->travel(here, t.start_location, now), t.release);
      if (start > t.latest_start()) continue;
      // The chance constraint: the departure must leave the window travel too.
      if (p.window_travel && now + p.window_travel->travel(here, t.start_location, now) > t.latest_start()) continue;
      const Time end = start + t.duration;
      used[j] = true;
      order.push_back(j);
      if (pickup) {
        load += t.transfer->load;
        if (!t.transfer->appearance.empty()) looks[t.transfer->appearance]++;
      }
      if (drop) {
        load -= t.transfer->load;
        if (!t.transfer->appearance.empty()) looks[t.transfer->appearance]--;
      }
      self(self, end, t.end_location, cost + (end - p.robot.time));
      if (pickup) {
        load -= t.transfer->load;
        if (!t.transfer->appearance.empty()) looks[t.transfer->appearance]--;
      }
      if (drop) {
        load += t.transfer->load;
        if (!t.transfer->appearance.empty()) looks[t.transfer->appearance]++;
      }
      order.pop_back();
      used[j] = false;
    }
  };
  extend(extend, p.robot.time, p.robot.location, Duration{0});
  return best;
}

}  // namespace rondo::schedule::testing
