#include "rondo/plan/value_iteration.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "reachability.h"

namespace rondo::plan {

Result<Solution> ValueIteration::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));
  const map::TopoMap& map = mdp.topology();

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

  // Q(i, e) = τ + p V(j) + (1 − p) V(i) under the values `v`; +inf for unusable edges and
  // unreachable ends.
  auto q_value = [&](const std::vector<double>& v, NodeIndex i, EdgeIndex e) {
    if (!mdp.usable(e)) return kInfinity;
    const double vj = v[map.to_index(e)];
    if (vj == kInfinity) return kInfinity;
    const EdgeOutcome& o = mdp.outcome(e);
    return o.expected_seconds + o.success_probability * vj + (1.0 - o.success_probability) * v[i];
  };

  const double tolerance = options_.tolerance > 0 ? options_.tolerance : 1e-6;
  SolveStatus status = SolveStatus::kSweepLimit;
  std::size_t sweeps = 0;
  std::vector<double> previous;
  while (sweeps < options_.max_sweeps) {
    ++sweeps;
    if (!options_.gauss_seidel) previous = value;
    const std::vector<double>& read = options_.gauss_seidel ? value : previous;
    double largest_change = 0.0;
    for (NodeIndex i : active) {
      double best = kInfinity;
      for (EdgeIndex e : map.out_edges(i)) best = std::min(best, q_value(read, i, e));
      // best is finite: i reaches the target, so some usable edge leads to a finite value.
      const double change = std::abs(best - value[i]);
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
    for (EdgeIndex e : map.out_edges(i)) {
      const NodeIndex j = map.to_index(e);
      if (!(value[j] < value[i])) continue;
      const double q = q_value(value, i, e);
      if (q < best) {
        best = q;
        const EdgeOutcome& o = mdp.outcome(e);
        steps[i] = {.from = i,
                    .edge = e,
                    .to = j,
                    .success_probability = o.success_probability,
                    .attempt_seconds = o.expected_seconds};
      }
    }
  }
  return Solution{.status = status, .policy = Policy(target, std::move(steps), std::move(value)), .sweeps = sweeps};
}

}  // namespace rondo::plan
