// A policy on the product of M_t with a task formula's automaton (product_mdp.h): for every
// (node, automaton state), the edge to try next and the expected time until the formula is
// satisfied. What the executor needs to follow a spec task and the scheduler to price it.
//
//   ProductPolicy policy = ProductExactSolver{}.solve(product).value().policy;
//   auto q = policy.start_state(here);                  // the start node is read first
//   while (!policy.satisfied(q)) {
//     EdgeIndex e = *policy.next_edge(here, q);         // nothing: the formula cannot be satisfied
//     ... on success: here = map.to_index(e); q = policy.after_reaching(q, here);
//   }
//   double eta = policy.expected_seconds(here, q);       // for the scheduler
//   std::optional<NodeIndex> end = policy.end_node(here, q);
//
// A ProductPolicy holds the automaton (shared) and the few numbers of each chosen edge, so it
// stays valid after the Mdp and the ProductMdp it came from are gone.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "rondo/ltl/automaton.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/policy.h"
#include "rondo/plan/travel_time_distribution.h"

namespace rondo::plan {

// One step: from `from` in automaton state `state`, try `edge` (to `to`) until it succeeds; the
// automaton is then in `next_state`.
struct ProductStep {
  NodeIndex from = 0;
  ltl::Automaton::State state = 0;
  EdgeIndex edge = Policy::kNoEdge;
  NodeIndex to = 0;
  ltl::Automaton::State next_state = 0;
  double success_probability = 1.0;
  double attempt_seconds = 0.0;
  bool operator==(const ProductStep&) const = default;
};

class ProductPolicy {
 public:
  using AutomatonState = ltl::Automaton::State;

  // `letters`: the automaton's letter of every map node; `steps` and `expected_seconds`: one per
  // product state (node × automaton states + q), a step's edge kNoEdge where there is none. The
  // solvers build policies; the constructor only checks sizes (std::invalid_argument on misuse).
  ProductPolicy(std::shared_ptr<const ltl::Automaton> automaton, std::vector<ltl::Automaton::Letter> letters,
                std::vector<ProductStep> steps, std::vector<double> expected_seconds);

  const ltl::Automaton& automaton() const { return *automaton_; }
  std::size_t node_count() const { return letters_.size(); }

  // The automaton, as the product sees it.
  AutomatonState after_reaching(AutomatonState q, NodeIndex node) const { return automaton_->next(q, letters_[node]); }
  AutomatonState start_state(NodeIndex node) const { return after_reaching(automaton_->initial(), node); }
  bool satisfied(AutomatonState q) const { return automaton_->accepting(q); }
  // The formula can no longer be satisfied, whatever the robot does.
  bool violated(AutomatonState q) const { return automaton_->rejecting(q); }

  // Preconditions below: node < node_count(), q < automaton().state_count().
  // The edge to try; nothing when satisfied and where the formula cannot be satisfied any more.
  std::optional<EdgeIndex> next_edge(NodeIndex node, AutomatonState q) const;
  std::optional<ProductStep> step(NodeIndex node, AutomatonState q) const;
  // Expected seconds until the formula is satisfied: 0 when it is, +inf when it cannot be.
  double expected_seconds(NodeIndex node, AutomatonState q) const { return expected_[index(node, q)]; }
  // The probability of satisfying the formula from here under this policy: 1 where the expected
  // time is finite, else 0 (a failed attempt leaves the robot where it was, so a route that can
  // be crossed is crossed with probability 1; docs/ltl.md).
  double satisfaction_probability(NodeIndex node, AutomatonState q) const {
    return expected_seconds(node, q) < kInfinity ? 1.0 : 0.0;
  }
  // The steps until the formula is satisfied (empty when it is, or cannot be). A failed attempt
  // changes nothing, so the route is the same whatever the attempts' luck.
  std::vector<ProductStep> route(NodeIndex node, AutomatonState q) const;
  // Where the route ends: the node at which the formula is expected to be satisfied; nothing
  // when it cannot be. For the scheduler's end location.
  std::optional<NodeIndex> end_node(NodeIndex node, AutomatonState q) const;
  // The distribution of the time until satisfied, as Policy::travel_time_distribution.
  TravelTimeDistribution travel_time_distribution(NodeIndex node, AutomatonState q,
                                                  const DistributionOptions& options = {}) const;

 private:
  std::size_t index(NodeIndex node, AutomatonState q) const { return node * automaton_->state_count() + q; }

  std::shared_ptr<const ltl::Automaton> automaton_;
  std::vector<ltl::Automaton::Letter> letters_;
  std::vector<ProductStep> steps_;
  std::vector<double> expected_;
};

}  // namespace rondo::plan
