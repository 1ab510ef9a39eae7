// Properties of planning on the product, on random maps of 2-12 nodes with random outcomes
// (p in [0.3, 1], some edges closed) and random formulas over their nodes (at most 3 operators
// deep): value iteration brackets the exact solver's expected times within its bound; following
// the exact policy yields a trace the direct evaluator says satisfies the formula, in the expected
// time; the probability of satisfying it, by a reference value iteration on probabilities, is 1
// exactly where the exact solver finds a finite time and 0 elsewhere; and where it is 0 the
// planner says why.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "ltl/formula_generators.h"
#include "random_map.h"
#include "rondo/ltl/trace_evaluator.h"
#include "rondo/plan/product_blockers.h"
#include "rondo/plan/product_solver.h"

namespace rondo::plan {
namespace {

struct Case {
  Case(map::TopoMap m, std::uint32_t seed, ltl::Formula f)
      : map(std::move(m)),
        mdp(Mdp::from_outcomes(map, testing::random_outcomes(map, {.seed = seed, .closed_fraction = 0.1,
                                                                    .min_probability = 0.3}),
                               Time{})
                .value()),
        formula(std::move(f)),
        automaton(std::make_shared<const ltl::Automaton>(ltl::Automaton::build(formula, {.max_states = 4096}).value())) {}
  map::TopoMap map;
  Mdp mdp;  // refers to `map`
  ltl::Formula formula;
  std::shared_ptr<const ltl::Automaton> automaton;
};

// Draws a small map (a random digraph with dead ends, or a grid of places connected both ways),
// its outcomes and a formula over its nodes, often under F or after an avoided node's U, so that
// most cases ask the robot to move. By pointer: the Mdp refers to the map, so the case must not move.
std::unique_ptr<Case> draw_case() {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  using ltl::testing::pick;
  auto size = [](int low, int high) { return static_cast<std::size_t>(pick(low, high)); };
  map::TopoMap m = pick(0, 2) == 0 ? testing::random_map({.nodes = size(2, 13), .seed = seed})
                                   : testing::building_map({.rows = size(1, 4),
                                                .columns = size(2, 5),
                                                .seed = seed,
                                                .wall_fraction = 0.2});
  std::vector<std::string> names;
  for (const map::Node& n : m.nodes()) names.push_back(n.name);
  ltl::Formula f = ltl::testing::draw_formula(3, names);
  switch (pick(0, 3)) {
    case 0: f = ltl::Formula::eventually(f); break;
    case 1: f = ltl::Formula::until(ltl::Formula::not_at(ltl::testing::pick_from(names)), f); break;
    default: break;
  }
  auto c = std::make_unique<Case>(std::move(m), seed, std::move(f));
  RC_PRE(c->automaton->state_count() > 1);  // not a constant: there is something to plan
  return c;
}

RC_GTEST_PROP(ProductProperties, ValueIterationBracketsTheExactExpectedTimes, ()) {
  const auto c = draw_case();
  const ProductMdp product = ProductMdp::build(c->mdp, c->automaton).value();
  const ProductSolution exact = ProductExactSolver{}.solve(product);
  const double tolerance = 1e-9;
  const ProductSolution vi =
      ProductValueIteration({.tolerance = tolerance, .max_sweeps = 200000, .gauss_seidel = *rc::gen::arbitrary<bool>()})
          .solve(product);
  RC_ASSERT(vi.status == SolveStatus::kConverged);
  std::size_t moving = 0;  // states with a finite, positive expected time
  for (ProductState s = 0; s < product.state_count(); ++s) {
    const NodeIndex n = product.node_of(s);
    const auto q = product.automaton_state_of(s);
    const double v = exact.policy.expected_seconds(n, q);
    const double upper = vi.policy.expected_seconds(n, q), lower = vi.lower_bound[s];
    RC_ASSERT((v == kInfinity) == (upper == kInfinity));
    if (v == kInfinity) continue;
    if (v > 0) ++moving;
    const double rounding = 1e-12 * std::max(1.0, v);  // sums of τ/p in another order
    RC_ASSERT(lower - rounding <= v);
    RC_ASSERT(v <= upper + rounding);
    RC_ASSERT(upper - lower <= tolerance * upper + rounding);
  }
  RC_TAG(moving == 0 ? "no state must move" : moving < 10 ? "1-9 states must move" : "10 or more states must move");
}

RC_GTEST_PROP(ProductProperties, FollowingTheExactPolicySatisfiesTheFormulaInTheExpectedTime, ()) {
  const auto c = draw_case();
  const ProductMdp product = ProductMdp::build(c->mdp, c->automaton).value();
  const ProductSolution exact = ProductExactSolver{}.solve(product);
  for (NodeIndex start = 0; start < product.node_count(); ++start) {
    const auto q = exact.policy.start_state(start);
    const double expected = exact.policy.expected_seconds(start, q);
    RC_ASSERT((expected < kInfinity) == !why_unsatisfiable(product, start, q).has_value());
    if (expected == kInfinity) continue;
    std::vector<std::string> trace = {c->map.node(start).name};
    double seconds = 0.0;
    for (const ProductStep& step : exact.policy.route(start, q)) {
      RC_ASSERT(step.from == c->map.from_index(step.edge));
      trace.push_back(c->map.node(step.to).name);
      seconds += c->mdp.expected_crossing_seconds(step.edge);
    }
    RC_ASSERT(ltl::satisfied(c->formula, trace));
    RC_ASSERT(std::abs(seconds - expected) <= 1e-9 * std::max(1.0, expected));
    RC_ASSERT(exact.policy.end_node(start, q) == c->map.find_node(trace.back()));
  }
}

// The largest probability of ever reaching an accepting state, by value iteration on
// probabilities from 0 (Gauss-Seidel; the iterates rise to it from below).
std::vector<double> reach_probability(const ProductMdp& product) {
  std::vector<double> p(product.state_count(), 0.0);
  for (ProductState s = 0; s < product.state_count(); ++s) p[s] = product.accepting(s) ? 1.0 : 0.0;
  for (int sweep = 0; sweep < 20000; ++sweep) {
    double change = 0.0;
    for (ProductState s = 0; s < product.state_count(); ++s) {
      if (product.accepting(s)) continue;
      const auto q = product.automaton_state_of(s);
      double best = 0.0;
      for (const Mdp::OutArc& a : product.mdp().usable_out(product.node_of(s))) {
        const ProductState t = product.state(a.to, product.after_reaching(q, a.to));
        best = std::max(best, a.success_probability * p[t] + (1.0 - a.success_probability) * p[s]);
      }
      change = std::max(change, best - p[s]);
      p[s] = best;
    }
    if (change < 1e-15) break;
  }
  return p;
}

RC_GTEST_PROP(ProductProperties, TheReachProbabilityIsOneWhereTheTimeIsFiniteAndZeroElsewhere, ()) {
  const auto c = draw_case();
  const ProductMdp product = ProductMdp::build(c->mdp, c->automaton).value();
  const ProductSolution exact = ProductExactSolver{}.solve(product);
  const std::vector<double> p = reach_probability(product);
  for (ProductState s = 0; s < product.state_count(); ++s) {
    const double v = exact.policy.expected_seconds(product.node_of(s), product.automaton_state_of(s));
    if (v < kInfinity)
      RC_ASSERT(p[s] > 1.0 - 1e-6);
    else
      RC_ASSERT(p[s] == 0.0);
  }
}

}  // namespace
}  // namespace rondo::plan
