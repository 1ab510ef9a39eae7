// Solvers of the product of M_t with a task formula's automaton (product_mdp.h): the policy that
// maximises the probability of satisfying the formula, then minimises the expected time.
//
//   ProductSolution s = ProductExactSolver{}.solve(product);                 // status kExact
//   ProductSolution v = ProductValueIteration({.tolerance = 1e-9}).solve(product);
//   v.lower_bound[s] <= optimal expected seconds <= v.policy's expected seconds (the upper bound)
//
// Why the exact solver is exact (docs/ltl.md): a failed attempt leaves the product state as it
// was, as in M_t, so the theorem of docs/planning.md holds on the product with the accepting
// states as one target: the reach probability is 1 from every state with a usable route to an
// accepting state and 0 from the others, and among policies that reach, the optimum is a
// shortest-path tree on τ/p, found by one reverse Dijkstra from all accepting states at once.
//
// ProductValueIteration is interval iteration: Bellman sweeps from below (V = 0) and from above
// (the value of the fewest-edges policy, a super-solution), which bracket the optimum at every
// sweep; it stops when the bracket is narrow enough. Its policy is greedy on the upper values,
// so its expected time is at most the upper bound: a proved bound, not a heuristic stop.
#pragma once

#include <cstddef>
#include <vector>

#include "rondo/plan/product_mdp.h"
#include "rondo/plan/product_policy.h"
#include "rondo/plan/solution.h"

namespace rondo::plan {

struct ProductSolution {
  SolveStatus status = SolveStatus::kExact;
  ProductPolicy policy;
  // Per product state, a lower bound of the optimal expected seconds (value iteration); the
  // policy's own values for the exact solver.
  std::vector<double> lower_bound;
  std::size_t sweeps = 0;  // value-iteration sweeps; 0 for the exact solver
};

class ProductExactSolver {
 public:
  // O((S + A) log S) for S product states and A = edges × automaton states arcs.
  ProductSolution solve(const ProductMdp& product) const;
};

struct ProductValueIterationOptions {
  // Stop when, on every state, upper − lower <= tolerance × upper.
  double tolerance = 1e-9;
  std::size_t max_sweeps = 100000;  // then status kSweepLimit, with the bracket reached so far
  bool gauss_seidel = false;        // update in place instead of from the previous sweep
};

class ProductValueIteration {
 public:
  explicit ProductValueIteration(const ProductValueIterationOptions& options = {}) : options_(options) {}
  ProductSolution solve(const ProductMdp& product) const;

 private:
  ProductValueIterationOptions options_;
};

}  // namespace rondo::plan
