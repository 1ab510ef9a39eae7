// Whether a finite trace (the nodes the robot reached, in order) satisfies a formula, computed
// directly from the semantics, without progression or automata: the reference the automaton is
// tested against.
//
//   std::vector<std::string> trace = {"Station", "WayPoint3", "WayPoint5"};
//   bool done = satisfied(parse_formula("F WayPoint3 & F WayPoint5").value(), trace);   // true
//
// The semantics (docs/ltl.md): a trace w of n nodes has positions 0 … n, where position n is its
// end. w satisfies f when f holds at position 0, with
//   true: everywhere; false: nowhere;
//   x (at node x), !x (not at x): at i < n when w[i] is x (is not x); never at the end;
//   f & g, f | g: as usual;  X f: at i < n when f holds at i + 1;
//   F f: f holds at some j in [i, n];  f U g: g holds at some j in [i, n] and f at every k in [i, j).
// So the end is where the trace stops and no node is known: only obligations that need no more
// nodes (true, F true, ...) hold there. A trace that satisfies a formula satisfies it whatever
// nodes are appended, the mark of co-safety.
#pragma once

#include <span>
#include <string>

#include "rondo/ltl/formula.h"

namespace rondo::ltl {

bool satisfied(const Formula& formula, std::span<const std::string> trace);

}  // namespace rondo::ltl
