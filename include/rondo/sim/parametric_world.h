// A simulated building described by its rhythms (docs/simulation.md, "Parametric world"): every
// edge takes its nominal time from the map geometry, with long-tailed noise and a base failure
// probability; *effects* change failure probability and speed of chosen edges at chosen times
// (a lunch crowd, doors closed out of hours, a corridor blocked on Wednesday afternoons); and a
// hidden two-state (normal / blocked) Markov process per edge makes failures come in bursts.
//
//   ParametricSpec spec;                                  // usually from load_world()
//   spec.effects.push_back({.name = "lunch", .edges = kitchen_edges,
//                           .when = {{.days = weekdays(), .from = hours(12), .to = hours(13)}},
//                           .failure_probability = 0.3, .duration_factor = 1.8});
//   ParametricWorld world(map, zone, spec);
//   EdgeSample s = world.sample_edge(edge, t, rng);
//
// Contract: as EdgeWorld. Closed edges, and edges in a shut spell, always fail. The burst state of
// an edge changes only with time; sampling one edge never changes another's state.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/edge_world.h"
#include "rondo/sim/time_condition.h"

namespace rondo::sim {

// Multiplicative noise on a nominal duration: lognormal with median 1 and spread `sigma`, times a
// Pareto(tail_alpha) factor, capped at tail_max, with probability tail_probability (the rare very
// slow attempt: a person in the way, a relocalisation).
struct DurationNoise {
  double sigma = 0.2;
  double tail_probability = 0.03;
  double tail_alpha = 1.5;
  double tail_max = 10.0;
  bool operator==(const DurationNoise&) const = default;
};

// How long a failed attempt takes, as a factor of the duration a success would have taken,
// uniform in [min_factor, max_factor] (the robot gives up early or retries until a timeout).
struct FailedDuration {
  double min_factor = 0.3;
  double max_factor = 1.5;
  bool operator==(const FailedDuration&) const = default;
};

// The hidden per-edge process: episodes of `normal` and `blocked` with exponential lengths of the
// given means; while blocked an attempt fails with failure_probability (on top of the rest) and
// takes duration_factor times longer. mean_blocked == 0 turns bursts off.
struct BurstSpec {
  Duration mean_normal = hours(12);
  Duration mean_blocked{0};
  double failure_probability = 0.6;
  double duration_factor = 1.5;
  bool operator==(const BurstSpec&) const = default;
};

// Spells of a door shut and open that last (someone closes their office for a while): while the
// effect is active, each door it selects alternates between open and shut spells of exponential
// lengths with these means, the same spell for both directions, and seen by the door sensor
// (closed_at). An edge with no door has spells of its own. The spells are drawn per local day
// from the world's seed (EdgeWorld::set_seed), the effect, the door and the day, starting in the
// stationary state: they do not depend on who looks, when, or in what order.
struct ShutSpells {
  Duration mean_open{0};
  Duration mean_shut{0};
  bool operator==(const ShutSpells&) const = default;
};

// A change to some edges at some times. Active at t when `when` is empty or one of it matches, and
// none of `unless` matches. Failure probabilities combine as independent causes:
// p = 1 - (1 - p_base)(1 - p_effect)...; duration factors multiply.
struct EdgeEffect {
  std::string name{};
  std::vector<map::EdgeIndex> edges{};  // resolved from the selectors of the YAML
  std::vector<TimeCondition> when{};
  std::vector<TimeCondition> unless{};
  double failure_probability = 0;
  double duration_factor = 1;
  bool closed = false;  // every attempt fails
  std::optional<ShutSpells> spells{};  // every attempt fails during a shut spell
  bool operator==(const EdgeEffect&) const = default;
};

struct ParametricSpec {
  double default_speed = 0.45;  // m/s for edges without a top speed (map::nominal_travel_time)
  double failure_probability = 0.02;
  DurationNoise noise{};
  FailedDuration failed{};
  BurstSpec bursts{};
  std::vector<EdgeEffect> effects{};
  bool operator==(const ParametricSpec&) const = default;
};

// What applies to one edge at one instant, before randomness: for tests and reports.
struct EdgeConditions {
  Duration nominal{0};
  double failure_probability = 0;
  double duration_factor = 1;
  bool closed = false;
  bool blocked = false;  // the burst state
};

class ParametricWorld final : public EdgeWorld {
 public:
  // Precondition: every index in spec.effects[*].edges is an edge of `map`.
  ParametricWorld(const map::TopoMap& map, TimeZone zone, ParametricSpec spec);

  EdgeSample sample_edge(map::EdgeIndex edge, Time start, Rng& rng) override;
  void set_seed(std::uint64_t seed) override;
  std::optional<bool> closed_at(map::EdgeIndex edge, Time t) const override;
  // Advances the edge's burst state to `start` (drawing from rng) and returns what applies.
  EdgeConditions conditions(map::EdgeIndex edge, Time start, Rng& rng);

  const ParametricSpec& spec() const { return spec_; }

 private:
  struct BurstState {
    bool blocked = false;
    bool started = false;
    Time last{};
  };
  bool advance_burst(map::EdgeIndex edge, Time t, Rng& rng);
  bool active(const EdgeEffect& effect, Time t) const;
  // Whether `effect` (active at t) has `edge` shut at t.
  bool shut(std::size_t effect, map::EdgeIndex edge, Time t) const;

  // One door's spells over one local day: the times it changes, from its state at midnight.
  struct SpellDay {
    std::chrono::year_month_day day{};
    bool shut_at_midnight = false;
    std::vector<Time> changes{};
  };

  TimeZone zone_;
  ParametricSpec spec_;
  std::vector<Duration> nominal_;                // per edge
  std::vector<std::vector<std::size_t>> effects_of_;  // per edge: indices into spec_.effects
  std::vector<BurstState> burst_;                // per edge
  std::vector<std::string> spell_key_;           // per edge: its door, else its id
  std::uint64_t seed_ = 0;
  // The day drawn last per (effect, door): a memo of a pure function of the seed and the time.
  mutable std::map<std::pair<std::size_t, std::string>, SpellDay> spells_;
};

}  // namespace rondo::sim
