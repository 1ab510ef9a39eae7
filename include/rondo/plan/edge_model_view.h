// What the planner needs to know about one edge at one time: the chance that an attempt to cross
// it succeeds and how long an attempt takes. The learned models (rondo::learn) and the no-data
// distance prior both answer through this one interface, so the MDP does not care which it gets.
//
//   DistancePrior prior(map);                                  // distance_prior.h
//   EdgeCrossing o = prior.outcome(edge, depart_at);
//   double expected_crossing = o.expected_seconds / o.success_probability;   // retries included
//
//   FunctionEdgeModels models([](map::EdgeIndex e, Time t) { return EdgeCrossing{0.9, 12.0}; });
//   models.set([](map::EdgeIndex, Time) { return EdgeCrossing{0.5, 12.0}; });  // version() moves on
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/travel_time_distribution.h"

namespace rondo::plan {

// One attempt to cross an edge (MISSION.md §4): it reaches the edge's end with probability
// `success_probability`, otherwise it leaves the robot where it started; either way it costs
// `expected_seconds`. The planner treats the attempt duration as that fixed value (the models
// give no more), so all the spread of a journey's time comes from the number of attempts.
struct EdgeCrossing {
  double success_probability = 1.0;  // in [0, 1]; out-of-range values are clamped, NaN means 0
  double expected_seconds = 0.0;     // >= 0; NaN or +inf makes the edge unusable
  bool operator==(const EdgeCrossing&) const = default;
};

// A read-only view of per-edge models at any time t.
//
// Contract for implementations: outcome() is deterministic and free of side effects for a given
// version(); version() changes (any new value) whenever the answers may have changed, e.g. after
// the models were refitted. Caches such as TravelPlanner compare versions to know when to drop
// what they hold. Edge indices are those of the map the planner was given.
//
// An online update changes a few edges only. A view that can tell which says so through
// changed_since(v): the edges whose answers may differ from those at version v. A cache entry
// filled at v then stays valid unless one of those edges touches it (travel_oracle.h,
// exec/map_travel.h). nullopt means "anything may have changed" (a new snapshot, or a version the
// view cannot account for): the default, so a view that says nothing empties caches as before.
class EdgeModelView {
 public:
  virtual ~EdgeModelView() = default;
  virtual EdgeCrossing outcome(map::EdgeIndex edge, Time at) const = 0;
  virtual std::uint64_t version() const = 0;
  // For bounds over every later departure (exec::TravelCache::lower_bound): an edge's answers at
  // t >= conditioned_until(edge) + memory() depend only on t's place in the (local) week; before
  // that they may also depend on t - conditioned_until(edge) (an online model's recency state).
  // The defaults: answers that depend on the time of week only.
  virtual Time conditioned_until(map::EdgeIndex /*edge*/) const { return Time{}; }
  virtual Duration memory() const { return Duration{0}; }
  // The attempt-duration laws the travel-time distribution uses: fills `leg`'s success_law and
  // failure_law for an attempt of `edge` starting at `at` (leg.attempt_seconds already set to its
  // expected seconds; it may also lower leg.success_probability, for attempts that end neither
  // way). Leaves them empty (each attempt lasts its expected seconds) by default. They change only
  // together with version().
  virtual void attempt_laws(map::EdgeIndex /*edge*/, Time /*at*/, RouteLeg& /*leg*/) const {}
  // Precondition: since <= version(). Empty when since == version().
  virtual std::optional<std::vector<map::EdgeIndex>> changed_since(std::uint64_t since) const {
    if (since == version()) return std::vector<map::EdgeIndex>{};
    return std::nullopt;
  }
};

// An EdgeModelView made of a function: for tests, benchmarks and adapters.
class FunctionEdgeModels final : public EdgeModelView {
 public:
  using Function = std::function<EdgeCrossing(map::EdgeIndex, Time)>;
  explicit FunctionEdgeModels(Function f) : f_(std::move(f)) {}

  EdgeCrossing outcome(map::EdgeIndex edge, Time at) const override { return f_(edge, at); }
  std::uint64_t version() const override { return version_; }

  // Replaces the function and moves the version on.
  void set(Function f) {
    f_ = std::move(f);
    ++version_;
  }

 private:
  Function f_;
  std::uint64_t version_ = 0;
};

}  // namespace rondo::plan
