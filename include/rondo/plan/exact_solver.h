// The exact policy solver for M_t. Because a failed attempt leaves the robot where it was, trying
// an edge e until it succeeds costs τ_e/p_e in expectation, and the optimal policy is a
// shortest-path tree to the target on those costs (proof: docs/planning.md). One reverse Dijkstra,
// O((V + E) log V), over the MDP's compressed rows of usable in-edges (Mdp::usable_in).
//
//   Result<Solution> s = ExactSolver{}.solve(mdp, target);   // status kExact
//   double eta = s->policy.expected_seconds(start);
//
// Unusable edges (p = 0, infinite τ) are never taken; nodes that cannot reach the target get
// +inf and no edge. Ties between equally good edges go to the one found first (the lowest
// in-edge position of the closer node): deterministic for a given map.
#pragma once

#include <cstdint>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/solution.h"

namespace rondo::plan {

class ExactSolver {
 public:
  // An error (kInvalidInput) only when target >= mdp.node_count(). Not thread-safe: a solver
  // keeps its scratch space (heap, settled flags) between calls, so use one per thread.
  Result<Solution> solve(const Mdp& mdp, NodeIndex target) const;

 private:
  // An indexed 4-ary min-heap of nodes keyed by their tentative cost, with decrease-key: at most
  // one entry per node. Kept between calls so that a solve allocates only its result.
  mutable std::vector<NodeIndex> heap_;
  mutable std::vector<std::uint32_t> position_;  // in heap_; kAbsent / kSettled otherwise
};

}  // namespace rondo::plan
