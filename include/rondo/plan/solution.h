// What a policy solver returns: a status, the policy, and how much work it took.
//
//   Result<Solution> s = ValueIteration({.tolerance = 1e-6}).solve(mdp, target);
//   if (!s) return s.error();                         // misuse: target not in the map
//   if (s->status == SolveStatus::kSweepLimit) warn("not converged");
//   use(s->policy);
#pragma once

#include <cstddef>

#include "rondo/plan/policy.h"

namespace rondo::plan {

// Outcomes, not errors: an unreachable target is a valid answer (every other node gets +inf).
enum class SolveStatus {
  kExact,       // the optimal policy, up to floating-point rounding (ExactSolver)
  kConverged,   // value iteration met its tolerance
  kSweepLimit,  // value iteration stopped at its sweep limit: the best policy so far
};

const char* to_string(SolveStatus status);

struct Solution {
  SolveStatus status = SolveStatus::kExact;
  Policy policy;
  std::size_t sweeps = 0;  // value-iteration sweeps over the nodes; 0 for the exact solver
};

}  // namespace rondo::plan
