// ProductExactSolver: one reverse Dijkstra (binary heap, lazy deletion) on τ/p from every
// accepting product state at once. The arcs into (j, q') are the usable in-edges (i, j) of M_t
// combined with the automaton states q that step to q' on reaching j.
#include <algorithm>
#include <functional>
#include <queue>
#include <utility>

#include "product_steps.h"
#include "rondo/plan/product_solver.h"

namespace rondo::plan {

ProductSolution ProductExactSolver::solve(const ProductMdp& product) const {
  const std::size_t n = product.state_count();
  std::vector<double> cost(n, kInfinity);
  std::vector<ProductStep> steps(n);
  std::vector<char> settled(n, 0);
  using Entry = std::pair<double, ProductState>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  for (ProductState s = 0; s < n; ++s)
    if (product.accepting(s)) {
      cost[s] = 0.0;
      heap.emplace(0.0, s);
    }
  while (!heap.empty()) {
    const auto [d, s] = heap.top();
    heap.pop();
    if (settled[s]) continue;
    settled[s] = 1;
    const NodeIndex to = product.node_of(s);
    const ProductMdp::AutomatonState reached = product.automaton_state_of(s);
    for (const Mdp::InArc& arc : product.mdp().usable_in(to)) {
      for (ProductMdp::AutomatonState q : product.predecessors(product.letter(to), reached)) {
        const ProductState u = product.state(arc.from, q);
        const double candidate = d + arc.crossing_seconds;
        if (settled[u] || product.accepting(u) || !(candidate < cost[u])) continue;
        cost[u] = candidate;
        steps[u] = product_step(product, arc.from, q, arc.edge);
        heap.emplace(candidate, u);
      }
    }
  }
  std::vector<double> lower = cost;
  return ProductSolution{.status = SolveStatus::kExact,
                         .policy = ProductPolicy(product.shared_automaton(),
                                                 {product.letters().begin(), product.letters().end()},
                                                 std::move(steps), std::move(cost)),
                         .lower_bound = std::move(lower),
                         .sweeps = 0};
}

}  // namespace rondo::plan
