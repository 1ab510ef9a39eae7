// Formula progression (docs/ltl.md, "The automaton"): what remains of a formula to satisfy after
// the robot reached one more node, in a canonical form so that equal obligations are equal values.
//
//   Formula f = canonical(parse_formula("F A & F B").value());
//   Formula g = progress(f, "A");            // F B
//   Formula h = progress(g, std::nullopt);   // F B: a node the formula does not name
//   progress(g, "B") == Formula::truth();    // done
//
// For a trace w = a·u (a a node, u the rest, possibly empty): w satisfies f exactly when u
// satisfies progress(f, a) (trace_evaluator.h gives the semantics), and a canonical formula holds
// on the empty trace exactly when it is `true`.
#pragma once

#include <optional>
#include <string_view>

#include "rondo/ltl/formula.h"

namespace rondo::ltl {

// An equivalent formula in canonical form (equivalent on every finite trace, the empty one
// included): X false = false; F true = true, F false = false, F F f = F f; f U true = true,
// f U false = false, false U f = f, true U f = F f, f U f = f; conjunctions and disjunctions in
// disjunctive normal form over atoms (propositions, negated propositions, X, F and U formulas),
// sorted by <=>, without repeats and without a conjunction that implies another; and, because
// the robot is at one node at a time, a & b = false and a & !a = false for nodes a != b,
// a & !b = a, and b implies !a. canonical(canonical(f)) == canonical(f).
Formula canonical(const Formula& formula);

// What remains of `formula` after the robot reaches `node` (nullopt: a node it does not name).
// Precondition: `formula` is canonical; the result is canonical too.
Formula progress(const Formula& formula, std::optional<std::string_view> node);

}  // namespace rondo::ltl
