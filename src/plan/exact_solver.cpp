#include "rondo/plan/exact_solver.h"

#include <functional>
#include <queue>
#include <utility>

#include <fmt/format.h>

namespace rondo::plan {

Result<Solution> ExactSolver::solve(const Mdp& mdp, NodeIndex target) const {
  const std::size_t n = mdp.node_count();
  if (target >= n) return Error::invalid(fmt::format("target node index {} is not below the node count {}", target, n));
  const map::TopoMap& map = mdp.topology();

  std::vector<double> cost(n, kInfinity);
  std::vector<PolicyStep> steps(n, PolicyStep{.edge = Policy::kNoEdge});
  std::vector<char> done(n, 0);  // bytes, not bits: tested in the inner loop
  struct Entry {
    double cost;
    NodeIndex node;
  };
  // Orders by cost only (costs are never NaN), a min-heap.
  auto later = [](const Entry& a, const Entry& b) { return a.cost > b.cost; };
  std::vector<Entry> heap_storage;
  heap_storage.reserve(n);
  std::priority_queue<Entry, std::vector<Entry>, decltype(later)> queue(later, std::move(heap_storage));
  cost[target] = 0.0;
  queue.push({0.0, target});
  // Reverse Dijkstra on the crossing costs τ/p: cost[u] is settled when u leaves the queue.
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (done[v]) continue;
    done[v] = 1;
    for (EdgeIndex e : map.in_edges(v)) {
      const NodeIndex u = map.from_index(e);
      if (done[u] || !mdp.usable(e)) continue;
      const double candidate = d + mdp.expected_crossing_seconds(e);
      if (candidate < cost[u]) {
        cost[u] = candidate;
        const EdgeOutcome& o = mdp.outcome(e);
        steps[u] = {.from = u,
                    .edge = e,
                    .to = v,
                    .success_probability = o.success_probability,
                    .attempt_seconds = o.expected_seconds};
        queue.push({candidate, u});
      }
    }
  }
  return Solution{
      .status = SolveStatus::kExact, .policy = Policy(target, std::move(steps), std::move(cost)), .sweeps = 0};
}

}  // namespace rondo::plan
