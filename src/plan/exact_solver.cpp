#include "rondo/plan/exact_solver.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <utility>

#include <fmt/format.h>

namespace rondo::plan {

// The state of one reverse Dijkstra: tentative costs, the chosen edges, and which nodes are final.
struct ExactSolver::Search {
  const Mdp& mdp;
  std::vector<double>& cost;
  std::vector<PolicyStep>& steps;
  std::vector<std::uint8_t>& settled;

  // Settles v at cost d (if not yet settled) and offers every unsettled node with a usable edge
  // into v the cost d + τ/p; `queue(u, c)` is called for each improvement.
  template <typename Queue>
  void settle(NodeIndex v, Queue&& queue) {
    if (settled[v]) return;
    settled[v] = 1;
    const double d = cost[v];
    for (const Mdp::InArc& arc : mdp.usable_in(v)) {
      const NodeIndex u = arc.from;
      const double candidate = d + arc.crossing_seconds;
      if (candidate < cost[u] && !settled[u]) {
        cost[u] = candidate;
        steps[u].edge = arc.edge;
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

// Dial's bucket queue: bucket k holds the nodes whose tentative cost lies in [kΔ, (k + 1)Δ), with
// Δ the cheapest usable crossing. Every node in the lowest non-empty bucket is final, in any
// order: a path that could still improve it would end with an edge costing at least Δ, from a
// node of a lower bucket, which is already settled. Live costs span less than max τ/p + Δ, so a
// ring of 2^k >= max/Δ + 2 buckets never wraps onto itself. Stale entries are skipped.
void ExactSolver::run_buckets(Search& search, NodeIndex target) const {
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
  buckets_[bucket_of(0.0)].push_back(target);
  auto queue = [&](NodeIndex u, double c) {
    buckets_[bucket_of(c)].push_back(u);
    ++live;
  };
  for (std::size_t k = 0; live > 0; k = (k + 1) & mask) {
    std::vector<NodeIndex>& bucket = buckets_[k];
    // Rounding may file an improvement into the bucket being emptied: indices, not iterators.
    for (std::size_t i = 0; i < bucket.size(); ++i) {
      --live;
      search.settle(bucket[i], queue);
    }
    bucket.clear();
  }
}

// A binary min-heap of (cost, node) with lazy deletion, for M_t whose crossing costs are too
// spread out for a bucket ring of options_.max_buckets.
void ExactSolver::run_heap(Search& search, NodeIndex target) const {
  constexpr std::greater<> kMinFirst;
  heap_.clear();
  heap_.emplace_back(0.0, target);
  auto queue = [&](NodeIndex u, double c) {
    heap_.emplace_back(c, u);
    std::push_heap(heap_.begin(), heap_.end(), kMinFirst);
  };
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), kMinFirst);
    const NodeIndex v = heap_.back().second;
    heap_.pop_back();
    search.settle(v, queue);
  }
}

Result<Solution> ExactSolver::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));

  std::vector<double> cost(n, kInfinity);
  std::vector<PolicyStep> steps(n, PolicyStep{.edge = Policy::kNoEdge});
  settled_.assign(n, 0);
  cost[target] = 0.0;
  Search search{mdp, cost, steps, settled_};
  // Reverse Dijkstra on the crossing costs τ/p (never NaN): cost[v] is final when v is settled.
  if (uses_buckets(mdp)) {
    run_buckets(search, target);
  } else {
    run_heap(search, target);
  }
  // The chosen edges' outcomes, once per node rather than once per improvement.
  for (NodeIndex u = 0; u < n; ++u) {
    PolicyStep& s = steps[u];
    if (s.edge == Policy::kNoEdge) continue;
    const EdgeOutcome& o = mdp.outcome(s.edge);
    s.from = u;
    s.to = mdp.topology().to_index(s.edge);
    s.success_probability = o.success_probability;
    s.attempt_seconds = o.expected_seconds;
  }
  return Solution{
      .status = SolveStatus::kExact, .policy = Policy(target, std::move(steps), std::move(cost)), .sweeps = 0};
}

}  // namespace rondo::plan
