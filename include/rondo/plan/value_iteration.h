// Value iteration on M_t: the textbook solver the published system used (through the PRISM
// model checker), kept as the reference the exact solver is tested and benchmarked against.
//
//   ValueIteration vi({.tolerance = 1e-6});
//   Result<Solution> s = vi.solve(mdp, target);   // status kConverged or kSweepLimit
//
// The Bellman update V(i) <- min_e [τ_e + p_e V(j) + (1 − p_e) V(i)] runs from V = 0, by default
// synchronously (Jacobi: every sweep reads the previous sweep's values, as PRISM's value iteration
// does) or in place (Gauss-Seidel, usually fewer sweeps), over the nodes that can reach the target
// by usable edges (the others get +inf first, so the iteration never chases an unreachable
// target). Starting from 0 the values rise monotonically towards the optimum and stay below it.
// It stops when the largest relative change of a sweep, |ΔV(i)| / V(i), is at most `tolerance`
// (PRISM's default criterion), or after `max_sweeps`. The criterion bounds the last step, not the
// distance to the optimum: where edges fail often (small p) the remaining error can be a few times
// the tolerance; see docs/planning.md.
//
// The greedy policy is extracted among edges that lead to a strictly lower value, so it never
// loops. After kSweepLimit a node may have a finite value but no such edge yet (no next_edge()).
#pragma once

#include <cstddef>

#include "rondo/core/result.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/solution.h"

namespace rondo::plan {

struct ValueIterationOptions {
  double tolerance = 1e-6;          // relative change per sweep at which to stop, > 0
  std::size_t max_sweeps = 100000;  // stop here at the latest (status kSweepLimit)
  bool gauss_seidel = false;        // update in place instead of from the previous sweep
};

class ValueIteration {
 public:
  explicit ValueIteration(const ValueIterationOptions& options = {}) : options_(options) {}
  // An error (kInvalidInput) only when target >= mdp.node_count().
  Result<Solution> solve(const Mdp& mdp, NodeIndex target) const;

 private:
  ValueIterationOptions options_;
};

}  // namespace rondo::plan
