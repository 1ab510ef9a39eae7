// ProductValueIteration: interval iteration on the product (product_solver.h; the proof of the
// bracket is in docs/ltl.md).
#include <algorithm>
#include <cmath>
#include <utility>

#include "product_steps.h"
#include "rondo/plan/product_solver.h"

namespace rondo::plan {

namespace {

// The starting bracket: upper = the value of the fewest-edges policy (a breadth-first tree from
// the accepting states over the product's reversed usable arcs; its value is the sum of τ/p along
// the tree, docs/planning.md), lower = 0; both +inf where no accepting state can be reached.
// Returns the states that can reach one without being accepting, in breadth-first order.
std::vector<ProductState> start_bracket(const ProductMdp& product, std::vector<double>& lower,
                                        std::vector<double>& upper) {
  std::vector<ProductState> order;
  for (ProductState s = 0; s < product.state_count(); ++s)
    if (product.accepting(s)) {
      lower[s] = upper[s] = 0.0;
      order.push_back(s);
    }
  const std::size_t accepting = order.size();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const ProductState s = order[k];
    const NodeIndex to = product.node_of(s);
    for (const Mdp::InArc& arc : product.mdp().usable_in(to))
      for (ProductMdp::AutomatonState q : product.predecessors(product.letter(to), product.automaton_state_of(s))) {
        const ProductState u = product.state(arc.from, q);
        if (upper[u] < kInfinity) continue;  // reached before, or accepting
        upper[u] = arc.crossing_seconds + upper[s];
        lower[u] = 0.0;
        order.push_back(u);
      }
  }
  order.erase(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(accepting));
  return order;
}

struct Bracket {
  double lower;
  double upper;
};

// One Bellman update of state s from the values `l` and `u`: min over its usable edges of
// τ + p V(next) + (1 − p) V(s), skipping edges to states that cannot reach acceptance.
Bracket bellman(const ProductMdp& product, ProductState s, const std::vector<double>& l, const std::vector<double>& u) {
  const NodeIndex i = product.node_of(s);
  const ProductMdp::AutomatonState q = product.automaton_state_of(s);
  Bracket best{kInfinity, kInfinity};
  for (const Mdp::OutArc& a : product.mdp().usable_out(i)) {
    const ProductState t = product.state(a.to, product.after_reaching(q, a.to));
    if (u[t] == kInfinity) continue;
    const double p = a.success_probability;
    best.lower = std::min(best.lower, a.attempt_seconds + p * l[t] + (1.0 - p) * l[s]);
    best.upper = std::min(best.upper, a.attempt_seconds + p * u[t] + (1.0 - p) * u[s]);
  }
  return best;
}

// The greedy policy on the upper values, among edges to strictly lower upper values (so it
// cannot loop; at a super-solution the greedy edge always qualifies: docs/ltl.md).
std::vector<ProductStep> greedy_steps(const ProductMdp& product, const std::vector<ProductState>& active,
                                      const std::vector<double>& u) {
  std::vector<ProductStep> steps(product.state_count());
  for (ProductState s : active) {
    const NodeIndex i = product.node_of(s);
    const ProductMdp::AutomatonState q = product.automaton_state_of(s);
    double best = kInfinity;
    for (const Mdp::OutArc& a : product.mdp().usable_out(i)) {
      const ProductState t = product.state(a.to, product.after_reaching(q, a.to));
      if (!(u[t] < u[s])) continue;
      const double value = a.attempt_seconds + a.success_probability * u[t] + (1.0 - a.success_probability) * u[s];
      if (value < best) {
        best = value;
        steps[s] = product_step(product, i, q, a.edge);
      }
    }
  }
  return steps;
}

}  // namespace

ProductSolution ProductValueIteration::solve(const ProductMdp& product) const {
  const std::size_t n = product.state_count();
  std::vector<double> lower(n, kInfinity), upper(n, kInfinity);
  const std::vector<ProductState> active = start_bracket(product, lower, upper);
  const double tolerance = options_.tolerance > 0 ? options_.tolerance : 1e-9;
  SolveStatus status = SolveStatus::kSweepLimit;
  std::size_t sweeps = 0;
  std::vector<double> read_lower = lower, read_upper = upper;  // Jacobi: the previous sweep
  while (sweeps < options_.max_sweeps) {
    ++sweeps;
    if (!options_.gauss_seidel) {
      read_lower = lower;
      read_upper = upper;
    }
    const std::vector<double>& l = options_.gauss_seidel ? lower : read_lower;
    const std::vector<double>& u = options_.gauss_seidel ? upper : read_upper;
    double widest = 0.0;
    for (ProductState s : active) {
      const Bracket b = bellman(product, s, l, u);
      // Both sequences are monotone in exact arithmetic; max / min keep them so under rounding.
      lower[s] = std::max(lower[s], b.lower);
      upper[s] = std::min(upper[s], b.upper);
      if (upper[s] > 0) widest = std::max(widest, (upper[s] - lower[s]) / upper[s]);
    }
    if (widest <= tolerance) {
      status = SolveStatus::kConverged;
      break;
    }
  }
  std::vector<ProductStep> steps = greedy_steps(product, active, upper);
  return ProductSolution{.status = status,
                         .policy = ProductPolicy(product.shared_automaton(),
                                                 {product.letters().begin(), product.letters().end()},
                                                 std::move(steps), std::move(upper)),
                         .lower_bound = std::move(lower),
                         .sweeps = sweeps};
}

}  // namespace rondo::plan
