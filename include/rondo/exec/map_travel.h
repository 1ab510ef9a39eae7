// The scheduler's travel oracle over the planner: expected travel time between map nodes at a
// departure time, as the policy of the time-indexed MDP gives it (plan::TravelPlanner), read at the
// start of each time slot and interpolated linearly in between.
//
//   TravelCache cache(planner);                 // one per executor: survives many problems
//   auto travel = std::make_shared<SchedulerTravel>(cache, std::vector<map::NodeIndex>{here, a, b});
//   problem.travel = travel;                    // location i of the problem is node nodes[i]
//
// Along the route (optional: TravelCache's route_threshold; docs/planning.md, "Travel times along
// the route"): the value at a slot start is the time-dependent arrival (each edge read in the slot
// the robot reaches it, plan::TravelPlanner::time_dependent_arrivals) where it differs from the
// departure slot's value by more than the threshold, and the departure slot's value otherwise.
//
// Interpolating between slot starts makes travel a continuous function of the departure time.
// FIFO (leaving later never arrives earlier) needs every slope >= -1: the value at the next slot
// start is raised to at least (value now - slot width) when needed, so FIFO always holds. An
// unreachable node gives kUnreachable, which no time window admits.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/policy.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/schedule/travel_oracle.h"

namespace rondo::exec {

inline constexpr Duration kUnreachable = hours(24 * 365);
// How far behind the slot asked for the travel caches keep what they hold (TravelCache's entries,
// and the M_t of the executor's planners): a day.
inline constexpr Duration kTravelKeepBehind = hours(24);
// TravelCache's count bound (see there): at least this many entries (about 0.3 MB of policies on
// the G4S map), and otherwise this many times the largest working set of its recent problems.
// The working sets set the bound whenever they are larger; the floor only keeps a few problems'
// worth when they are small. It was 256: a service whose problems read fewer entries then filled
// its cache up to 256 over its first hours of wall time, for no answer it needed (docs/
// operations.md, "Memory over time", session 16; `rondo run`'s reports are the same either way).
inline constexpr std::size_t kTravelCacheFloor = 64;
inline constexpr std::size_t kTravelCacheWorkingSets = 2;

// Expected node-to-node seconds per slot start, shared by every problem of one executor. It keeps
// the planner's policy to each (slot start, target) asked for, with the models' version() it is
// valid at. When the models move on, an entry asks models->changed_since(): it stays when no
// changed edge touches it (plan::Policy::survives_edge_change with the edge's new τ/p at that slot
// start), and is solved again otherwise; everything is dropped when the models cannot say what
// changed (a refit). The lower bounds re-read only the changed edges' weekly minima, and are
// recomputed when one of those minima moved. So an online update of one edge leaves the entries
// it does not touch, and every answer equals what a fresh cache would give.
//
// Two bounds keep the cache the same size however long the robot has lived. Entries for slots
// more than a day before the latest one filled are dropped (departures move forward with the
// clock). And the count: each SchedulerTravel made over the cache (one per scheduling problem)
// opens a generation; the entries read during a generation are its working set (a day's problem
// reads targets x slots of the day). When a generation opens, the entries read longest ago go
// until at most max(kTravelCacheFloor, kTravelCacheWorkingSets x the largest working set of the
// last kRecentGenerations) are left. The previous generation's entries are the most recent, so
// they always stay: eviction never makes the next, similar problem solve its policies again, and
// never happens inside a solve. A service that sends the robot to many places (each target of
// the day is an entry per slot) holds what its recent problems read, not every place of the day.
//
// With a route threshold, the time-dependent arrivals from each (slot start, source) asked for are
// kept too, valid at one models' version (computed again when it moves on: one time-dependent
// Dijkstra), under the same two bounds with their own working sets.
class TravelCache {
 public:
  // `planner` must read `models`; the map and the planner must outlive the cache. Without a
  // `route_threshold`, every value is the departure slot's (the published system).
  TravelCache(const map::TopoMap& map, std::shared_ptr<const plan::EdgeModelView> models, plan::TravelPlanner& planner,
              Duration slot_width, std::optional<Duration> route_threshold = std::nullopt);
  // E(from, to) at the start of the slot that contains `depart`, as a Duration (kUnreachable):
  // along the route where that differs from the departure slot's by more than the threshold.
  Duration at_slot(map::NodeIndex from, map::NodeIndex to, Time slot_start) const;
  // E(from, to, depart) interpolated between slot starts, FIFO-repaired (see above).
  Duration travel(map::NodeIndex from, map::NodeIndex to, Time depart) const;
  // The `level`-quantile of the travel time from `from` to `to` at the start of the slot that
  // contains `depart`: the policy's route with each edge's attempts geometric in its success
  // probability and each attempt's duration from the models' laws (EdgeModelView::attempt_laws:
  // successful and failed attempts apart; none: the expected seconds), as plan::
  // TravelTimeDistribution gives it (its upper bracket, so never below the model's quantile).
  // Interpolated between slot starts and FIFO-repaired as travel() is. Each (slot, target, source)
  // is computed once per level and kept with its policy. Always the departure slot's reading: the
  // route threshold does not apply (a distribution along the time-dependent route is not built).
  Duration quantile_at_slot(map::NodeIndex from, map::NodeIndex to, Time slot_start, double level) const;
  Duration quantile_travel(map::NodeIndex from, map::NodeIndex to, Time depart, double level) const;
  // A lower bound of travel(from, to, t) over every t: the shortest path over per-edge minima of
  // the expected crossing time τ/p read at every slot start of one week. Exact for models that
  // repeat weekly (ours do: time-of-day and day-of-week bins); otherwise a schedule stays feasible
  // (travel() decides feasibility) but a solver may prune too eagerly. Along the route it stays a
  // bound: a time-dependent arrival is a path's sum of c_e(s_e) >= the edges' week minima, plus
  // waiting >= 0; interpolation and the FIFO repair only mix and raise values that are all above it.
  Duration lower_bound(map::NodeIndex from, map::NodeIndex to) const;
  Time slot_start(Time t) const { return planner_->slot_start(t); }
  Duration slot_width() const { return slot_width_; }
  // The models' version(): every value above stays the same while it does.
  std::uint64_t models_version() const;
  // travel() and quantile_travel() with the value at each slot start read through `at`
  // (SchedulerTravel's table of them).
  template <class AtSlot>
  Duration interpolate(Time depart, const AtSlot& at) const;
  plan::TravelPlanner& planner() const { return *planner_; }
  // Cached (slot, target) entries, and how many were solved again / kept after a model change.
  std::size_t cached_count() const { return policies_.size(); }
  std::size_t resolved_count() const { return resolved_; }
  // Policies solved in all (entries filled, and solved again).
  std::size_t solved_count() const { return solved_; }
  std::size_t kept_count() const { return kept_; }
  // Opens a generation (SchedulerTravel's constructor calls it) and evicts down to the bound.
  void begin_problem() const;
  // Entries read in the previous generation, and how many entries the count bound has evicted.
  std::size_t last_working_set() const { return recent_sets_[(generation_ - 1) % kRecentGenerations]; }
  std::size_t evicted_count() const { return evicted_; }
  std::optional<Duration> route_threshold() const { return route_threshold_; }
  // Kept (slot start, source) time-dependent arrivals, and how many searches filled them.
  std::size_t arrivals_count() const { return arrivals_.size(); }
  std::size_t route_searches() const { return route_searches_; }

 private:
  static constexpr std::size_t kRecentGenerations = 8;
  using WorkingSets = std::array<std::size_t, kRecentGenerations>;  // entries read, by generation
  struct Arrivals {
    std::vector<double> arrival_seconds;  // time-dependent, from the source to every node
    std::uint64_t version = 0;
    std::uint64_t used = 0;
  };
  struct Entry {
    plan::Policy policy;
    std::uint64_t version = 0;  // models->version() it is valid at
    std::uint64_t used = 0;     // the generation it was last read in
    // Quantile seconds of the policy's travel time per source node at `level` (NaN: not yet read).
    double level = 0;
    std::vector<double> quantile_seconds{};
  };
  // The policy to `to` at `slot_start`, valid at the current version.
  // The entry of the policy to `to` at `slot_start`, valid at the current version, with what is
  // kept beside it; read in the current generation.
  Entry& entry(map::NodeIndex to, Time slot_start) const;
  const plan::Policy& policy(map::NodeIndex to, Time slot_start) const { return entry(to, slot_start).policy; }
  // The time-dependent arrivals from `from` at `slot_start`, valid at the current version.
  const Arrivals& arrivals(map::NodeIndex from, Time slot_start) const;
  template <class E>
  E& touch(E& entry, WorkingSets& sets) const;
  void evict_to_bound() const;
  bool refresh(Entry& entry, Time slot_start) const;
  void refresh_lower_bounds() const;
  double edge_week_min(map::EdgeIndex e) const;

  const map::TopoMap* map_;
  std::shared_ptr<const plan::EdgeModelView> models_;
  plan::TravelPlanner* planner_;
  Duration slot_width_;
  std::optional<Duration> route_threshold_;
  mutable std::map<std::pair<Time, map::NodeIndex>, Entry> policies_;  // by (slot start, target)
  mutable std::map<std::pair<Time, map::NodeIndex>, Arrivals> arrivals_;    // by (slot start, source)
  mutable std::size_t resolved_ = 0, kept_ = 0, evicted_ = 0, solved_ = 0, route_searches_ = 0;
  mutable std::uint64_t generation_ = 1;
  mutable WorkingSets recent_sets_{};        // of policies_
  mutable WorkingSets recent_arrival_sets_{};  // of arrivals_
  mutable std::uint64_t lower_version_ = 0;                            // of edge_min_seconds_
  mutable std::vector<double> edge_min_seconds_;                       // empty until first needed
  mutable std::map<map::NodeIndex, std::vector<double>> lower_from_;  // per source: seconds to all
};

// What a solve reads again and again: the value at a slot start between two of a problem's
// locations. A solver's label extensions ask for the same few slots of the same pairs thousands
// of times, and each TravelCache read is two ordered-map lookups and a version check (more than
// half of a lone robot's run in the fleet example, docs/fleet.md). So each problem's oracle keeps the
// values it has read, in a table per slot start, for as long as the models stay at the version
// they were read at; a change of version empties it. Every value is the cache's, to the bit.
class SlotTable {
 public:
  explicit SlotTable(std::size_t locations) : locations_(locations) {}
  // The value for (from, to) at `slot_start`, from `read()` the first time.
  template <class Read>
  Duration get(std::uint64_t version, Time slot_start, Duration slot_width, std::size_t from, std::size_t to,
               const Read& read);

 private:
  static constexpr std::int64_t kNotRead = -1;
  // Null for a slot start off the grid of the first one read (not met: the planner's slots are
  // one width apart), which is then read each time.
  std::int64_t* cell(Time slot_start, Duration slot_width, std::size_t from, std::size_t to);

  std::size_t locations_;
  std::uint64_t version_ = 0;
  Time first_{};                                               // the slot start of slots_[0]
  std::vector<std::vector<std::vector<std::int64_t>>> slots_;  // [slot][from][to], milliseconds
};

template <class Read>
Duration SlotTable::get(std::uint64_t version, Time slot_start, Duration slot_width, std::size_t from, std::size_t to,
                        const Read& read) {
  if (version != version_) {
    slots_.clear();
    version_ = version;
  }
  std::int64_t* ms = cell(slot_start, slot_width, from, to);
  if (ms == nullptr) return read();
  if (*ms == kNotRead) *ms = read().count();
  return Duration{*ms};
}

template <class AtSlot>
Duration TravelCache::interpolate(Time depart, const AtSlot& at) const {
  const Time start = planner_->slot_start(depart);
  const Time next = start + slot_width_;
  const Duration here = at(start);
  if (here >= kUnreachable) return kUnreachable;
  Duration there = at(next);
  if (there >= kUnreachable) return here;       // closed later: the value now holds within the slot
  there = std::max(there, here - slot_width_);  // FIFO: slope >= -1
  const double f = static_cast<double>((depart - start).count()) / static_cast<double>(slot_width_.count());
  const double ms = static_cast<double>(here.count()) + f * static_cast<double>((there - here).count());
  return Duration{static_cast<std::int64_t>(std::llround(ms))};
}

// The chance constraint's window travel (schedule::Problem::window_travel): the quantile of
// the travel time at level 1 − α over the same cache and nodes. Made with the problem's
// SchedulerTravel, whose generation it reads in.
class SchedulerQuantileTravel final : public schedule::TravelOracle {
 public:
  // `speed`: the robot's factor (Building::speeds); the cache's standard times are divided by it.
  SchedulerQuantileTravel(const TravelCache& cache, std::vector<map::NodeIndex> nodes, double level,
                          double speed = 1.0);
  std::size_t location_count() const override { return nodes_.size(); }
  Duration travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const override;
  // Zero: the solvers read lower bounds from the expected travel only.
  Duration lower_bound(schedule::LocationIndex, schedule::LocationIndex) const override { return Duration{0}; }
  bool time_dependent() const override { return true; }

 private:
  const TravelCache* cache_;
  std::vector<map::NodeIndex> nodes_;
  double level_;
  double speed_;
  mutable SlotTable values_;
};

class SchedulerTravel final : public schedule::TravelOracle {
 public:
  // Opens a generation of `cache` (TravelCache::begin_problem): make one per problem. `speed`: the
  // robot's factor (Building::speeds); the cache's standard times are divided by it, at each slot
  // start before the interpolation (which keeps FIFO).
  SchedulerTravel(const TravelCache& cache, std::vector<map::NodeIndex> nodes, double speed = 1.0);
  std::size_t location_count() const override { return nodes_.size(); }
  Duration travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const override;
  Duration lower_bound(schedule::LocationIndex from, schedule::LocationIndex to) const override;
  bool time_dependent() const override { return true; }
  map::NodeIndex node(schedule::LocationIndex i) const { return nodes_[i]; }

 private:
  const TravelCache* cache_;
  std::vector<map::NodeIndex> nodes_;
  double speed_;
  mutable SlotTable values_;
};

}  // namespace rondo::exec
