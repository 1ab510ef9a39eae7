// What the planner needs to know about one edge at one time: the chance that an attempt to cross
// it succeeds and how long an attempt takes. The learned models (rondo::learn) and the no-data
// distance prior both answer through this one interface, so the MDP does not care which it gets.
//
//   DistancePrior prior(map);                                  // distance_prior.h
//   EdgeOutcome o = prior.outcome(edge, depart_at);
//   double expected_crossing = o.expected_seconds / o.success_probability;   // retries included
//
//   FunctionEdgeModels models([](map::EdgeIndex e, Time t) { return EdgeOutcome{0.9, 12.0}; });
//   models.set([](map::EdgeIndex, Time) { return EdgeOutcome{0.5, 12.0}; });  // version() moves on
#pragma once

#include <cstdint>
#include <functional>
#include <utility>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::plan {

// One attempt to cross an edge (MISSION.md §4): it reaches the edge's end with probability
// `success_probability`, otherwise it leaves the robot where it started; either way it costs
// `expected_seconds`. The planner treats the attempt duration as that fixed value (the models
// give no more), so all the spread of a journey's time comes from the number of attempts.
struct EdgeOutcome {
  double success_probability = 1.0;  // in [0, 1]; out-of-range values are clamped, NaN means 0
  double expected_seconds = 0.0;     // >= 0; NaN or +inf makes the edge unusable
  bool operator==(const EdgeOutcome&) const = default;
};

// A read-only view of per-edge models at any time t.
//
// Contract for implementations: outcome() is deterministic and free of side effects for a given
// version(); version() changes (any new value) whenever the answers may have changed, e.g. after
// the models were refitted. Caches such as TravelOracle compare versions to know when to drop
// what they hold. Edge indices are those of the map the planner was given.
class EdgeModelView {
 public:
  virtual ~EdgeModelView() = default;
  virtual EdgeOutcome outcome(map::EdgeIndex edge, Time at) const = 0;
  virtual std::uint64_t version() const = 0;
};

// An EdgeModelView made of a function: for tests, benchmarks and adapters.
class FunctionEdgeModels final : public EdgeModelView {
 public:
  using Function = std::function<EdgeOutcome(map::EdgeIndex, Time)>;
  explicit FunctionEdgeModels(Function f) : f_(std::move(f)) {}

  EdgeOutcome outcome(map::EdgeIndex edge, Time at) const override { return f_(edge, at); }
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
