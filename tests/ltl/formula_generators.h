// Random formulas of the co-safe fragment and random traces, for RapidCheck properties. Sizes are
// bounded by a depth, so no seed can make a property run long.
//
//   Formula f = draw_formula(3);                   // inside a property: draws with operator*
//   std::vector<std::string> w = draw_trace(f, 8);  // nodes of f and one other, up to 8 long
#pragma once

#include <rapidcheck.h>

#include <string>
#include <vector>

#include "rondo/ltl/formula.h"

namespace rondo::ltl::testing {

// A choice in [low, high), uniform whatever RapidCheck's current size (gen::inRange scales with
// it, which would make the first hundred formulas almost all constants); it still shrinks to low.
inline int pick(int low, int high) { return *rc::gen::resize(100, rc::gen::inRange(low, high)); }

template <class T>
const T& pick_from(const std::vector<T>& items) {
  return items[static_cast<std::size_t>(pick(0, static_cast<int>(items.size())))];
}

// Plain names, names that need quotes (a space, an operator's letter, a quote, UTF-8).
inline const std::vector<std::string>& node_pool() {
  static const std::vector<std::string> pool = {"a", "b", "c", "WayPoint12", "Room 1.2", "X", "say \"hi\"", "café"};
  return pool;
}

inline Formula draw_leaf(const std::vector<std::string>& nodes) {
  switch (pick(0, 10)) {
    case 0: return Formula::truth();
    case 1: return Formula::falsity();
    case 2:
    case 3:
    case 4: return Formula::not_at(pick_from(nodes));
    default: return Formula::at(pick_from(nodes));
  }
}

// A formula at most `depth` operators deep over `nodes`.
inline Formula draw_formula(int depth, const std::vector<std::string>& nodes) {
  if (depth <= 0) return draw_leaf(nodes);
  switch (pick(0, 7)) {
    case 0: return draw_leaf(nodes);
    case 1: return Formula::next(draw_formula(depth - 1, nodes));
    case 2: return Formula::eventually(draw_formula(depth - 1, nodes));
    case 3: return Formula::until(draw_formula(depth - 1, nodes), draw_formula(depth - 1, nodes));
    default: {
      std::vector<Formula> operands;
      const int n = pick(2, 4);
      for (int i = 0; i < n; ++i) operands.push_back(draw_formula(depth - 1, nodes));
      return pick(0, 2) == 0 ? Formula::all_of(std::move(operands)) : Formula::any_of(std::move(operands));
    }
  }
}

// The same over the first `node_count` names of the pool.
inline Formula draw_formula(int depth, std::size_t node_count = 4) {
  return draw_formula(depth, std::vector<std::string>(node_pool().begin(),
                                                      node_pool().begin() + static_cast<std::ptrdiff_t>(node_count)));
}

// A trace of up to `max_length` nodes: the formula's nodes and one it does not name.
inline std::vector<std::string> draw_trace(const Formula& f, int max_length) {
  std::vector<std::string> letters = named_nodes(f);
  letters.push_back("elsewhere");
  std::vector<std::string> trace;
  const int n = pick(0, max_length + 1);
  for (int i = 0; i < n; ++i) trace.push_back(pick_from(letters));
  return trace;
}

}  // namespace rondo::ltl::testing
