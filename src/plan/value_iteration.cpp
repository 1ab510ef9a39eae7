#include "rondo/plan/value_iteration.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "reachability.h"

namespace rondo::plan {

Result<Solution> ValueIteration::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));

  // Nodes that cannot reach the target are +inf from the start and never updated: without this
  // their values would grow without bound and the iteration would never converge.
  const std::vector<bool> reach = can_reach(mdp, target);
  std::vector<NodeIndex> active;
  std::vector<double> value(n, kInfinity);
  for (NodeIndex i = 0; i < n; ++i) {
    if (!reach[i]) continue;
    value[i] = 0.0;
    if (i != target) active.push_back(i);
  }

  // Q(i, e) = τ + p V(j) + (1 − p) V(i) under the values `v`, over the MDP's usable out-edges;
  // +inf for unreachable ends.
  auto q_value = [](const std::vector<double>& v, NodeIndex i, const Mdp::OutArc& a) {
    const double vj = v[a.to];
    if (vj == kInfinity) return kInfinity;
    return a.attempt_seconds + a.success_probability * vj + (1.0 - a.success_probability) * v[i];
  };

  const double tolerance = options_.tolerance > 0 ? options_.tolerance : 1e-6;
  SolveStatus status = SolveStatus::kSweepLimit;
  std::size_t sweeps = 0;
  // Jacobi reads the previous sweep (`read`) and writes `value`; the two buffers swap roles.
  std::vector<double> previous = value;
  while (sweeps < options_.max_sweeps) {
    ++sweeps;
    if (!options_.gauss_seidel) std::swap(previous, value);
    const std::vector<double>& read = options_.gauss_seidel ? value : previous;
    double largest_change = 0.0;
    for (NodeIndex i : active) {
      double best = kInfinity;
      for (const Mdp::OutArc& a : mdp.usable_out(i)) best = std::min(best, q_value(read, i, a));
      // best is finite: i reaches the target, so some usable edge leads to a finite value.
      const double change = std::abs(best - read[i]);
      if (best > 0) largest_change = std::max(largest_change, change / best);
      value[i] = best;
    }
    if (largest_change <= tolerance) {
      status = SolveStatus::kConverged;
      break;
    }
  }

  // The greedy policy, among edges to strictly lower values: values fall along it, so it cannot
  // loop. At the fixed point the greedy edge always qualifies (V(j) = V(i) − τ/p < V(i)).
  std::vector<PolicyStep> steps(n, PolicyStep{.edge = Policy::kNoEdge});
  for (NodeIndex i : active) {
    double best = kInfinity;
    for (const Mdp::OutArc& a : mdp.usable_out(i)) {
      if (!(value[a.to] < value[i])) continue;
      const double q = q_value(value, i, a);
      if (q < best) {
        best = q;
        steps[i] = {.from = i,
                    .edge = a.edge,
                    .to = a.to,
                    .success_probability = a.success_probability,
                    .attempt_seconds = a.attempt_seconds};
      }
    }
  }
  return Solution{.status = status, .policy = Policy(target, std::move(steps), std::move(value)), .sweeps = sweeps};
}

}  // namespace rondo::plan
