// The product of M_t (mdp.h) with the automaton of a co-safe task formula (ltl/automaton.h), for
// tasks written as formulas over the map's nodes (docs/ltl.md, "Planning on the product"). A
// state is (node, automaton state), the automaton state having read every node reached so far,
// this node included. Taking edge e = (i, j) from (i, q) reaches (j, δ(q, j)) with probability
// p_e(t) and stays at (i, q) otherwise (a failed attempt reaches no new node), costing τ_e(t)
// either way: exactly M_t's outcomes. States whose automaton state accepts are the goal.
//
//   auto automaton = std::make_shared<const ltl::Automaton>(ltl::Automaton::build(formula).value());
//   Mdp mdp = Mdp::build(map, models, depart_at);
//   Result<ProductMdp> product = ProductMdp::build(mdp, automaton);  // error: a node not in the map
//   ProductMdp::AutomatonState q = product->start_state(here);        // the start node is read first
//
// Lifetime: a ProductMdp refers to its Mdp (and so to the map); both must outlive it.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/ltl/automaton.h"
#include "rondo/plan/mdp.h"

namespace rondo::plan {

// A product state's index: node × automaton_state_count() + automaton state.
using ProductState = std::size_t;

class ProductMdp {
 public:
  using AutomatonState = ltl::Automaton::State;
  using Letter = ltl::Automaton::Letter;

  // An error (kNotFound) when the formula names a node the map does not have.
  static Result<ProductMdp> build(const Mdp& mdp, std::shared_ptr<const ltl::Automaton> automaton);

  const Mdp& mdp() const { return *mdp_; }
  const ltl::Automaton& automaton() const { return *automaton_; }
  const std::shared_ptr<const ltl::Automaton>& shared_automaton() const { return automaton_; }
  std::size_t node_count() const { return mdp_->node_count(); }
  std::size_t automaton_state_count() const { return automaton_->state_count(); }
  std::size_t state_count() const { return node_count() * automaton_state_count(); }

  // Preconditions below: node < node_count(), q < automaton_state_count(), s < state_count().
  ProductState state(NodeIndex node, AutomatonState q) const { return node * automaton_state_count() + q; }
  NodeIndex node_of(ProductState s) const { return s / automaton_state_count(); }
  AutomatonState automaton_state_of(ProductState s) const {
    return static_cast<AutomatonState>(s % automaton_state_count());
  }
  // The automaton's letter for being at `node` (the map's node names against the formula's).
  Letter letter(NodeIndex node) const { return letters_[node]; }
  std::span<const Letter> letters() const { return letters_; }
  AutomatonState after_reaching(AutomatonState q, NodeIndex node) const { return automaton_->next(q, letters_[node]); }
  // The automaton state of a robot that starts at `node`: the initial state after reading it.
  AutomatonState start_state(NodeIndex node) const { return after_reaching(automaton_->initial(), node); }
  bool accepting(ProductState s) const { return automaton_->accepting(automaton_state_of(s)); }
  bool rejecting(ProductState s) const { return automaton_->rejecting(automaton_state_of(s)); }

  // The automaton states q with δ(q, a) = to (for the solvers' backward searches).
  std::span<const AutomatonState> predecessors(Letter a, AutomatonState to) const {
    const std::size_t row = a * automaton_state_count() + to;
    return {pred_.data() + pred_start_[row], pred_.data() + pred_start_[row + 1]};
  }

 private:
  ProductMdp(const Mdp& mdp, std::shared_ptr<const ltl::Automaton> automaton, std::vector<Letter> letters);

  const Mdp* mdp_;
  std::shared_ptr<const ltl::Automaton> automaton_;
  std::vector<Letter> letters_;           // one per node
  std::vector<std::size_t> pred_start_;   // letters × automaton states + 1
  std::vector<AutomatonState> pred_;
};

}  // namespace rondo::plan
