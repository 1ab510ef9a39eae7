#include "rondo/plan/exact_solver.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>

#include <fmt/format.h>

#include "region_search.h"

namespace rondo::plan {

static_assert(Mdp::kNoExit == Policy::kNoEdge, "an exit's edge is a policy's edge");

// The state of one reverse Dijkstra: tentative costs, the chosen edges, and which nodes are final.
struct ExactSolver::Search {
  const Mdp& mdp;
  std::span<double> cost;
  std::span<EdgeIndex> edge;
  std::span<std::uint8_t> settled;

  // Settles v at its cost d (if not yet settled) and offers every unsettled node with a usable
  // edge into v the cost d + τ/p; `queue(u, c)` is called for each improvement. kCoreOnly: only
  // arcs between core nodes (Mdp::core_in), for searches that leave the dead ends to their exits.
  template <bool kCoreOnly, typename Queue>
  void settle(NodeIndex v, Queue&& queue) {
    if (settled[v]) return;
    settled[v] = 1;
    const double d = cost[v];
    for (const Mdp::InArc& arc : kCoreOnly ? mdp.core_in(v) : mdp.usable_in(v)) {
      const NodeIndex u = arc.from;
      const double candidate = d + arc.crossing_seconds;
      if (candidate < cost[u] && !settled[u]) {
        cost[u] = candidate;
        edge[u] = arc.edge;
        queue(u, candidate);
      }
    }
  }
};

bool ExactSolver::uses_buckets(const Mdp& mdp) const {
  const double width = mdp.min_crossing_seconds();
  if (!(width > 0) || !std::isfinite(width) || options_.max_buckets < 2) return false;
  return mdp.max_crossing_seconds() / width <= static_cast<double>(options_.max_buckets - 2);
}

// The widest bucket ring a solver keeps between solves (about 100 KB of empty buckets).
constexpr std::size_t kKeptBuckets = 4096;

// Dial's bucket queue: bucket k holds the nodes whose tentative cost lies in [kΔ, (k + 1)Δ), with
// Δ the cheapest usable crossing. Every node in the lowest non-empty bucket is final, in any
// order: a path that could still improve it would end with an edge costing at least Δ, from a
// node of a lower bucket, which is already settled. Live costs span less than max τ/p + Δ, so a
// ring of 2^k >= max/Δ + 2 buckets never wraps onto itself. Stale entries are skipped.
template <bool kCoreOnly>
void ExactSolver::run_buckets(Search& search, NodeIndex source) const {
  const Mdp& mdp = search.mdp;
  const double inverse_width = 1.0 / mdp.min_crossing_seconds();
  const std::size_t ring = std::bit_ceil(static_cast<std::size_t>(mdp.max_crossing_seconds() * inverse_width) + 2);
  if (buckets_.size() < ring) buckets_.resize(ring);
  const std::size_t mask = ring - 1;
  // Through a signed integer: one instruction, and costs stay far below 2^63 widths (the ring is
  // at most max_buckets wide, so a cost is at most node_count × max_buckets widths).
  auto bucket_of = [&](double c) {
    return static_cast<std::size_t>(static_cast<std::int64_t>(c * inverse_width)) & mask;
  };
  std::size_t live = 1;
  const std::size_t first = bucket_of(search.cost[source]);
  buckets_[first].push_back(source);
  auto queue = [&](NodeIndex u, double c) {
    buckets_[bucket_of(c)].push_back(u);
    ++live;
  };
  for (std::size_t k = first; live > 0; k = (k + 1) & mask) {
    std::vector<NodeIndex>& bucket = buckets_[k];
    // Rounding may file an improvement into the bucket being emptied: indices, not iterators.
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      --live;
      search.settle<kCoreOnly>(bucket[i], queue);
    }
    bucket.clear();
  }
  // A wide ring is released after its solve. One slot whose M_t spreads its crossing costs widely
  // (an edge expected to stay shut for a long time: a large τ/p) needs up to max_buckets buckets,
  // 24 bytes each (1.5 MB at 2^16); kept, that would be held for good by every planner that ever
  // met such a slot (docs/operations.md, "Memory over time"). Such a solve walks the whole ring
  // anyway, so building it again costs about as much as the walk.
  if (buckets_.size() > kKeptBuckets) std::vector<std::vector<NodeIndex>>().swap(buckets_);
}

// A binary min-heap of (cost, node) with lazy deletion, for M_t whose crossing costs are too
// spread out for a bucket ring of options_.max_buckets.
template <bool kCoreOnly>
void ExactSolver::run_heap(Search& search, NodeIndex source) const {
  constexpr std::greater<> kMinFirst;
  heap_.clear();
  heap_.emplace_back(search.cost[source], source);
  auto queue = [&](NodeIndex u, double c) {
    heap_.emplace_back(c, u);
    std::push_heap(heap_.begin(), heap_.end(), kMinFirst);
  };
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), kMinFirst);
    const NodeIndex v = heap_.back().second;
    heap_.pop_back();
    search.settle<kCoreOnly>(v, queue);
  }
}

// Reverse Dijkstra from `source`, whose cost is already set, over every usable arc or over the
// arcs between core nodes only.
void ExactSolver::run(Search& search, NodeIndex source, bool core_only) const {
  const bool buckets = uses_buckets(search.mdp);
  if (core_only) {
    buckets ? run_buckets<true>(search, source) : run_heap<true>(search, source);
  } else {
    buckets ? run_buckets<false>(search, source) : run_heap<false>(search, source);
  }
}

// Every dead-end region but `skip` whose door has a finite cost: a node of the region goes to the
// door by its exit route, whatever the target outside (the door separates them).
void ExactSolver::fill_regions(Search& search, std::optional<std::uint32_t> skip) const {
  const DeadEnds& dead_ends = search.mdp.dead_ends();
  const std::span<const Mdp::Exit> exits = search.mdp.exits();
  for (std::uint32_t r = 0; r < dead_ends.region_count(); ++r) {
    const double at_door = search.cost[dead_ends.door(r)];
    if (r == skip || at_door == kInfinity) continue;
    const Mdp::Exit* exit = exits.data() + dead_ends.first_member(r);
    for (NodeIndex v : dead_ends.nodes(r)) {
      if (exit->seconds < kInfinity) {
        search.cost[v] = exit->seconds + at_door;
        search.edge[v] = exit->edge;
      }
      ++exit;
    }
  }
}

Result<Solution> ExactSolver::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));

  std::vector<double> cost(n, kInfinity);
  edge_.assign(n, Policy::kNoEdge);
  settled_.assign(n, 0);
  Search search{mdp, cost, edge_, settled_};
  // Reverse Dijkstra on the crossing costs τ/p (never NaN): cost[v] is final when v is settled.
  const DeadEnds& dead_ends = mdp.dead_ends();
  if (!options_.use_dead_ends || dead_ends.region_count() == 0) {
    cost[target] = 0.0;
    run(search, target, false);
  } else if (const std::optional<std::uint32_t> region = dead_ends.region_of(target)) {
    // Inside the target's region first; everything else reaches the target through the door.
    detail::search_region(mdp, *region, target, cost, edge_, settled_);
    const NodeIndex door = dead_ends.door(*region);
    if (cost[door] < kInfinity) {
      settled_[door] = 0;  // settled again by the core search, at its cost from the region
      run(search, door, true);
      fill_regions(search, region);
    }
  } else {
    cost[target] = 0.0;
    run(search, target, true);
    fill_regions(search, std::nullopt);
  }

  // The chosen edges' outcomes, once per node rather than once per improvement.
  std::vector<PolicyStep> steps(n, PolicyStep{.edge = Policy::kNoEdge});
  for (NodeIndex u = 0; u < n; ++u) {
    const EdgeIndex e = edge_[u];
    if (e == Policy::kNoEdge || u == target) continue;
    const EdgeCrossing& o = mdp.outcome(e);
    steps[u] = {.from = u,
                .edge = e,
                .to = mdp.topology().to_index(e),
                .success_probability = o.success_probability,
                .attempt_seconds = o.expected_seconds};
  }
  return Solution{
      .status = SolveStatus::kExact, .policy = Policy(target, std::move(steps), std::move(cost)), .sweeps = 0};
}

}  // namespace rondo::plan
