#include "found_blocked.h"

#include <algorithm>

#include "rondo/plan/travel_planner.h"

namespace rondo::exec {

void FoundBlocked::failed(map::EdgeIndex edge, double p, Time now) {
  Edge& e = edges_[edge];
  if (e.run.failures > 0 && now - e.run.last > kRunMemory) e.run = {};
  ++e.run.failures;
  e.run.chance *= 1 - std::clamp(p, 0.0, 1.0);
  e.run.last = now;
}

void FoundBlocked::passed(map::EdgeIndex edge) { edges_.erase(edge); }

FoundBlocked::Run FoundBlocked::run(map::EdgeIndex edge, Time now) const {
  const auto it = edges_.find(edge);
  if (it == edges_.end() || now - it->second.run.last > kRunMemory) return {};
  return it->second.run;
}

void FoundBlocked::hold(map::EdgeIndex edge, Time until) { edges_[edge].until = until; }

std::optional<Time> FoundBlocked::held_until(map::EdgeIndex edge, Time now) const {
  const auto it = edges_.find(edge);
  if (it == edges_.end() || !it->second.until || *it->second.until <= now) return std::nullopt;
  return it->second.until;
}

std::optional<std::pair<Time, double>> passable_again(const plan::EdgeModelView& models,
                                                      const plan::TravelPlanner& planner, Duration slot_width,
                                                      map::EdgeIndex edge, Time now, Time until) {
  for (Time t = planner.slot_start(now) + slot_width; t <= until; t += slot_width) {
    const double p = models.outcome(edge, t).success_probability;
    if (p >= kLikelyPassable) return std::pair{t, p};
  }
  return std::nullopt;
}

}  // namespace rondo::exec
