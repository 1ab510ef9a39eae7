// The exact policy solver for M_t. Because a failed attempt leaves the robot where it was, trying
// an edge e until it succeeds costs τ_e/p_e in expectation, and the optimal policy is a
// shortest-path tree to the target on those costs (proof: docs/planning.md). One reverse Dijkstra
// over the MDP's compressed rows of usable in-edges. By default it searches only the map's core
// (Mdp::core_in) and gives every dead-end region (dead_ends.h) its precomputed route to its door
// (Mdp::exits); a target inside a region is first searched for inside that region. Its priority
// queue is Dial's ring of buckets of width min τ/p when max τ/p / min τ/p is at most
// `max_buckets` − 2 (O(V + E + cost span / width)), else a binary heap of (cost, node) pairs,
// O((V + E) log V); both with lazy deletion. bench/plan_bench.cpp shows the gains.
//
//   Result<Solution> s = ExactSolver{}.solve(mdp, target);   // status kExact
//   double eta = s->policy.expected_seconds(start);
//   ExactSolver heap_only({.max_buckets = 0});               // always the binary heap
//   ExactSolver plain({.use_dead_ends = false});             // search every node
//
// Unusable edges (p = 0, infinite τ) are never taken; nodes that cannot reach the target get
// +inf and no edge. Costs agree with any other Dijkstra up to floating-point rounding; between
// equally good edges the choice is deterministic for a given M_t and queue.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/solution.h"

namespace rondo::plan {

struct ExactSolverOptions {
  // The largest ring of buckets worth using; below 2: always the heap.
  std::size_t max_buckets = std::size_t{1} << 16;
  // Search the core only and give the map's dead ends (Mdp::dead_ends) their precomputed routes
  // to their doors; false: search every node (the plain reverse Dijkstra, kept for comparison).
  bool use_dead_ends = true;
};

class ExactSolver {
 public:
  explicit ExactSolver(ExactSolverOptions options = {}) : options_(options) {}
  // Whether solve() uses the bucket ring on `mdp` (else the binary heap).
  bool uses_buckets(const Mdp& mdp) const;

  // An error (kInvalidInput) only when target >= mdp.node_count(). Not thread-safe: a solver
  // keeps its scratch space (heap, settled flags) between calls, so use one per thread.
  Result<Solution> solve(const Mdp& mdp, NodeIndex target) const;

 private:
  struct Search;  // one solve's costs, chosen edges and settled flags
  void run(Search& search, NodeIndex source, bool core_only) const;
  template <bool kCoreOnly>
  void run_buckets(Search& search, NodeIndex source) const;
  template <bool kCoreOnly>
  void run_heap(Search& search, NodeIndex source) const;
  void fill_regions(Search& search, std::optional<std::uint32_t> skip) const;

  ExactSolverOptions options_;
  // Scratch space kept between calls so that a solve allocates only its result. Queues may hold
  // stale entries (nodes settled since).
  mutable std::vector<std::pair<double, NodeIndex>> heap_;  // (tentative cost, node)
  mutable std::vector<std::vector<NodeIndex>> buckets_;     // the ring
  mutable std::vector<std::uint8_t> settled_;               // per node
  mutable std::vector<EdgeIndex> edge_;                     // per node: the edge chosen so far
};

}  // namespace rondo::plan
