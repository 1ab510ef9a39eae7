// Expected travel times E(a, b, t) between any two nodes for a departure time t: what the
// scheduler uses as its travel durations. Two readings of the models:
// - static per departure (the published system): M_t is built at the start of t's time slot and
//   solved exactly; every edge is read at that one time. Cached per (slot, target).
// - time-dependent: each edge is read at the time the robot reaches it, by a time-dependent
//   Dijkstra over FIFO-repaired edge arrival functions (docs/planning.md): leaving later never
//   arrives earlier, because the robot may wait at a node for a better slot.
//
//   auto models = std::make_shared<DistancePrior>(map);
//   TravelPlanner oracle(map, models, {.slot_width = minutes(15)});
//   double e = oracle.expected_seconds(a, b, depart_at);          // +inf when b is unreachable
//   const Policy& p = oracle.policy(b, depart_at);
//   TimedRoute r = oracle.time_dependent_route(a, b, depart_at);  // r.arrival_seconds
//
// Not thread-safe: queries fill caches. Every cached M_t and policy remembers the models->version()
// it was last valid at. When the version has moved on, the entry asks models->changed_since(): an
// M_t re-reads only the changed edges at its time (a copy with them patched when they differ); a
// policy is kept when no changed edge touches it (Policy::survives_edge_change: the policy does
// not take the edge and the edge did not become a shortcut), else solved again. When the models
// cannot say what changed (a new snapshot), the entry is rebuilt. So an online update of one edge
// (LearnedEdgeModels::observe) costs one model read per cached slot used afterwards, not a refill
// of every cache. The map must outlive the oracle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/policy.h"

namespace rondo::plan {

struct TravelPlannerOptions {
  Duration slot_width = minutes(15);      // > 0; slots are aligned to 00:00 UTC (Unix time 0)
  std::size_t max_cached_policies = 512;  // the policy cache is emptied when it would grow past this
  std::size_t max_cached_slots = 1024;    // likewise for the per-slot MDPs
  // When set, building a slot's M_t drops the cached ones that start more than this before it:
  // a service's departures move forward with its clock, so the cache holds about this span (plus
  // what lies ahead) however long it runs. Unset: only max_cached_slots bounds it.
  std::optional<Duration> keep_behind{};
  // How far ahead the time-dependent variant looks for a slot where waiting pays off (FIFO repair),
  // and beyond which an edge closed now counts as closed for good.
  Duration max_wait = hours(24);
};

// One step of a time-dependent route. Times are seconds after the departure.
struct TimedStep {
  EdgeIndex edge = 0;
  NodeIndex from = 0;
  NodeIndex to = 0;
  double reach_seconds = 0.0;   // when the robot reaches `from`
  double start_seconds = 0.0;   // when it starts trying the edge (later than reach_seconds if waiting pays)
  double arrive_seconds = 0.0;  // start + τ/p read at start_seconds
};

struct TimedRoute {
  bool reachable = false;
  double arrival_seconds = kInfinity;  // expected seconds from departure to arrival; +inf if unreachable
  std::vector<TimedStep> steps;
};

class TravelPlanner {
 public:
  // Precondition: models is not null, options.slot_width > 0 (std::invalid_argument otherwise).
  TravelPlanner(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
               const TravelPlannerOptions& options = {});

  // Static per departure: E(from, to) in M_t with t the start of depart's slot. 0 when from == to.
  // Preconditions for every query: from, to < the map's node_count() (std::out_of_range otherwise).
  double expected_seconds(NodeIndex from, NodeIndex to, Time depart);
  // The optimal policy to `target` in the same M_t. The reference is valid until the next query.
  const Policy& policy(NodeIndex target, Time depart);
  // The same policy, solved and not kept in the policy cache (the slot's M_t is): for callers that
  // keep the policies they ask for themselves (exec::TravelCache), so each is held once.
  Policy solve_policy(NodeIndex target, Time depart);
  // The snapshot for depart's slot. The pointer stays valid after the caches are emptied.
  std::shared_ptr<const Mdp> mdp_at(Time depart);

  // Time-dependent: each edge read in the slot in which the robot starts trying it.
  TimedRoute time_dependent_route(NodeIndex from, NodeIndex to, Time depart);
  double time_dependent_expected_seconds(NodeIndex from, NodeIndex to, Time depart) {
    return time_dependent_route(from, to, depart).arrival_seconds;
  }
  // The same reading from one source to every node: expected seconds from `depart` to the arrival
  // at each node (+inf where unreachable; 0 at `from`), by the same search run to the end.
  std::vector<double> time_dependent_arrivals(NodeIndex from, Time depart);

  // The start of the slot that contains t.
  Time slot_start(Time t) const;
  std::size_t cached_policy_count() const { return policies_.size(); }
  std::size_t cached_slot_count() const { return slots_.size(); }
  // How many cached policies were solved again after a model change, and how many were kept.
  std::size_t policies_resolved() const { return resolved_; }
  std::size_t policies_kept() const { return kept_; }

 private:
  struct CachedMdp {
    std::shared_ptr<const Mdp> mdp;
    std::uint64_t version = 0;  // models->version() it is valid at
  };
  struct CachedPolicy {
    Policy policy;
    std::uint64_t version = 0;
  };
  std::int64_t slot_of(Time t) const;
  // The slot's M_t, valid at the models' current version (built, patched or as cached).
  const std::shared_ptr<const Mdp>& slot_entry(std::int64_t slot);
  const Mdp& slot_mdp(std::int64_t slot) { return *slot_entry(slot); }
  // Brings a cached M_t to the current version; false when it must be built again.
  bool refresh(CachedMdp& entry);
  // Whether a cached policy is still optimal at the current version (then marks it so).
  bool refresh(CachedPolicy& entry, std::int64_t slot);
  // Earliest expected arrival at the end of `edge` when reaching its start at `t` seconds after
  // `depart` (FIFO-repaired); also when to start trying it.
  double edge_arrival(EdgeIndex edge, Time depart, double t, double* start_out);
  // The time-dependent Dijkstra from `from` at `depart` (docs/planning.md): arrival seconds per
  // node and the step that reached it; stops once `stop_at` is settled, else runs to the end.
  struct TimedSearch {
    std::vector<double> arrival;
    std::vector<TimedStep> via;
    std::vector<bool> has_via;
  };
  TimedSearch time_dependent_search(NodeIndex from, Time depart, std::optional<NodeIndex> stop_at);

  const map::TopoMap* map_;
  std::shared_ptr<const EdgeModelView> models_;
  TravelPlannerOptions options_;
  std::shared_ptr<const DeadEnds> dead_ends_;  // the map's, shared by every slot's M_t
  std::map<std::int64_t, CachedMdp> slots_;
  std::map<std::pair<std::int64_t, NodeIndex>, CachedPolicy> policies_;
  std::size_t resolved_ = 0, kept_ = 0;
  ExactSolver solver_;  // its scratch space is reused by every solve
};

}  // namespace rondo::plan
