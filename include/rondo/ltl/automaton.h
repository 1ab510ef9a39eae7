// The deterministic finite automaton of a co-safe formula, by formula progression (progression.h):
// a state is what remains to satisfy, in canonical form; the accepting state is `true` (satisfied)
// and the rejecting sink is `false` (can no longer be satisfied). The robot is at one node at a
// time, so the letters are the nodes the formula names plus one for "any other node".
//
//   Result<Automaton> a = Automaton::build(parse_formula("F A & F B").value());
//   Automaton::State q = a->next(a->initial(), "Station");   // read the start node first
//   q = a->next(q, "A");
//   a->obligation(q);                                       // F B
//   a->accepting(a->next(q, "B"));                          // true
//   a->accepts(std::vector<std::string>{"Station", "A", "B"});   // the same, in one call
//
// Size: building explores the progressed formulas breadth first and refuses the formula as soon
// as there are more than `max_states` of them (an error, never a long computation). The automaton
// is then minimised (Moore's partition refinement), so equivalent obligations share a state and
// every state that can no longer reach acceptance is the one rejecting sink.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/ltl/formula.h"

namespace rondo::ltl {

struct AutomatonOptions {
  std::size_t max_states = 256;         // progressed formulas explored before minimising
  std::size_t max_formula_size = 4096;  // operators and propositions in one progressed formula
  std::size_t max_depth = 128;          // nesting of the formula given
  bool minimise = true;
};

class Automaton {
 public:
  using State = std::uint32_t;
  using Letter = std::uint32_t;

  // An error (kInvalidInput) when a limit of `options` is passed; the message names it.
  static Result<Automaton> build(const Formula& formula, const AutomatonOptions& options = {});

  // The formula given, in canonical form (progression.h).
  const Formula& formula() const { return formula_; }

  // Letters: 0 … nodes().size() − 1 are "at nodes()[i]"; other_letter() is any other node.
  std::span<const std::string> nodes() const { return nodes_; }
  std::size_t letter_count() const { return nodes_.size() + 1; }
  Letter other_letter() const { return static_cast<Letter>(nodes_.size()); }
  Letter letter_of(std::string_view node) const;

  std::size_t state_count() const { return accepting_.size(); }
  // Progressed formulas explored before minimising (state_count() when not minimised).
  std::size_t explored_states() const { return explored_; }
  State initial() const { return 0; }
  // Preconditions: q < state_count(), a < letter_count().
  State next(State q, Letter a) const { return delta_[q * letter_count() + a]; }
  State next(State q, std::string_view node) const { return next(q, letter_of(node)); }
  // Satisfied: the obligation is `true`; every later letter stays here.
  bool accepting(State q) const { return accepting_[q] != 0; }
  // No continuation can satisfy the formula any more (the obligation `false`, or one equivalent).
  bool rejecting(State q) const { return rejecting_[q] != 0; }
  // What remains to satisfy in state q: the simplest progressed formula of the state.
  const Formula& obligation(State q) const { return obligations_[q]; }

  // Whether the trace (starting with the robot's first node) satisfies the formula.
  bool accepts(std::span<const std::string> trace) const;

 private:
  Automaton() = default;
  void find_rejecting();

  Formula formula_;
  std::vector<std::string> nodes_;
  std::vector<State> delta_;  // state_count() × letter_count()
  std::vector<char> accepting_, rejecting_;
  std::vector<Formula> obligations_;
  std::size_t explored_ = 0;
};

}  // namespace rondo::ltl
