// The exact policy solver for M_t. Because a failed attempt leaves the robot where it was, trying
// an edge e until it succeeds costs τ_e/p_e in expectation, and the optimal policy is a
// shortest-path tree to the target on those costs (proof: docs/planning.md). One reverse Dijkstra,
// O((V + E) log V).
//
//   Result<Solution> s = ExactSolver{}.solve(mdp, target);   // status kExact
//   double eta = s->policy.expected_seconds(start);
//
// Unusable edges (p = 0, infinite τ) are never taken; nodes that cannot reach the target get
// +inf and no edge. Ties between equally good edges go to the one found first (the lowest
// in-edge position of the closer node): deterministic for a given map.
#pragma once

#include "rondo/core/result.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/solution.h"

namespace rondo::plan {

class ExactSolver {
 public:
  // An error (kInvalidInput) only when target >= mdp.node_count().
  Result<Solution> solve(const Mdp& mdp, NodeIndex target) const;
};

}  // namespace rondo::plan
