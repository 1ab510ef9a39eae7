// Moore's partition refinement for the automaton of automaton.h: which states are equivalent.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rondo::ltl {

// A complete DFA: delta[q * letters + a]; every state reachable from state 0.
struct TransitionTable {
  std::size_t letters = 0;
  std::vector<std::uint32_t> delta;
  std::vector<char> accepting;
  std::size_t state_count() const { return accepting.size(); }
};

// For every state, its class in the minimal automaton: two states share a class exactly when
// they accept the same continuations. Classes are numbered in breadth-first order from state 0's
// class (so state 0 is in class 0) over the letters in order. O(rounds × states × letters log).
std::vector<std::uint32_t> equivalence_classes(const TransitionTable& table);

}  // namespace rondo::ltl
