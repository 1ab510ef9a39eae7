// What the robot's journeys found of its edges, known to every journey (docs/executor.md, "A way
// found blocked"): per edge, the failures in a row, whichever journey made them (a task's or the
// executor's own: NavigateStep is the one way the robot moves, so every attempt passes here), the
// chance the live model gave that run, and until when every journey holds the edge blocked, once
// one found it so. A success of the edge forgets it all. It keeps no model of its own: when to
// look again is the live model's answer (passable_again), and the nightly refit does not read it.
//
//   FoundBlocked found;
//   found.failed(edge, 0.95, now);                    // an attempt the live model gave p = 0.95
//   if (found.run(edge, now).refuted()) found.hold(edge, *passable_again(models, ...));
//   if (auto until = found.held_until(edge, now)) ...  // another journey waits for it
#pragma once

#include <optional>
#include <unordered_map>
#include <utility>

#include "rondo/core/time.h"
#include "rondo/exec/executor_types.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan {
class TravelPlanner;
}

namespace rondo::exec {

class FoundBlocked {
 public:
  // A run of failures older than this is forgotten: a failure that long after the last one is met
  // afresh.
  static constexpr Duration kRunMemory = hours(24);

  struct Run {
    int failures = 0;    // in a row, across journeys
    double chance = 1;   // the product of 1 − p over them, p the live model's when each was sent
    Time last{};         // when the last one ended
    // Two or more failures that the live model gave less than kRefuted of a chance together: it
    // has not learned this closure yet.
    bool refuted() const { return failures >= 2 && chance < kRefuted; }
  };

  // An attempt of `edge` that the live model gave `p` of passing failed at `now`.
  void failed(map::EdgeIndex edge, double p, Time now);
  // An attempt of `edge` passed: its run and its hold are over.
  void passed(map::EdgeIndex edge);
  // The failures of `edge` in a row (none, or older than kRunMemory: failures 0).
  Run run(map::EdgeIndex edge, Time now) const;
  // Every journey holds `edge` blocked until `until` (a later hold replaces it).
  void hold(map::EdgeIndex edge, Time until);
  // Until when `edge` is held blocked, when that is after `now`.
  std::optional<Time> held_until(map::EdgeIndex edge, Time now) const;

 private:
  struct Edge {
    Run run;
    std::optional<Time> until;
  };
  std::unordered_map<map::EdgeIndex, Edge> edges_;
};

// The first slot start after `now`, up to `until`, at which `models` hold `edge` likely passable
// (kLikelyPassable), with its probability then.
std::optional<std::pair<Time, double>> passable_again(const plan::EdgeModelView& models,
                                                      const plan::TravelPlanner& planner, Duration slot_width,
                                                      map::EdgeIndex edge, Time now, Time until);

}  // namespace rondo::exec
