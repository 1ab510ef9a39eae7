// Properties on random formulas of the fragment and random traces: the automaton accepts a trace
// exactly when the direct evaluator says it satisfies the formula (minimised or not); accepting
// and rejecting states are closed; satisfaction survives any continuation; the canonical form
// keeps the meaning and is a fixed point. Formulas are at most 3 operators deep over 4 nodes,
// traces at most 8 nodes long, so every case is small.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

#include "formula_generators.h"
#include "rondo/ltl/automaton.h"
#include "rondo/ltl/progression.h"
#include "rondo/ltl/trace_evaluator.h"

namespace rondo::ltl {
namespace {

using testing::draw_formula;
using testing::draw_trace;

RC_GTEST_PROP(AutomatonProperties, TheAutomatonAcceptsExactlyTheTracesThatSatisfyTheFormula, ()) {
  const Formula f = draw_formula(3);
  const bool minimise = *rc::gen::arbitrary<bool>();
  // Depth 3 explores at most a few hundred states; the limit is raised so none is discarded.
  const Automaton a = Automaton::build(f, {.max_states = 1 << 14, .minimise = minimise}).value();
  RC_TAG(a.state_count() > 2 ? "over 2 states" : "2 states or fewer");
  for (int k = 0; k < 8; ++k) {
    const std::vector<std::string> trace = draw_trace(f, 8);
    RC_ASSERT(a.accepts(trace) == satisfied(f, trace));
  }
}

RC_GTEST_PROP(AutomatonProperties, RejectingStatesNeverAcceptAndAcceptingStatesStay, ()) {
  const Formula f = draw_formula(3);
  const Automaton a = Automaton::build(f, {.max_states = 1 << 14}).value();
  for (Automaton::State q = 0; q < a.state_count(); ++q)
    for (Automaton::Letter l = 0; l < a.letter_count(); ++l) {
      if (a.accepting(q)) RC_ASSERT(a.next(q, l) == q);
      if (a.rejecting(q)) RC_ASSERT(a.rejecting(a.next(q, l)));
    }
}

RC_GTEST_PROP(AutomatonProperties, SatisfactionSurvivesAnyContinuation, ()) {
  const Formula f = draw_formula(3);
  const std::vector<std::string> trace = draw_trace(f, 6);
  std::vector<std::string> longer = trace;
  for (const std::string& node : draw_trace(f, 4)) longer.push_back(node);
  if (satisfied(f, trace)) RC_ASSERT(satisfied(f, longer));
}

RC_GTEST_PROP(AutomatonProperties, TheCanonicalFormKeepsTheMeaningAndIsAFixedPoint, ()) {
  const Formula f = draw_formula(3);
  const Formula c = canonical(f);
  RC_ASSERT(canonical(c) == c);
  for (int k = 0; k < 8; ++k) {
    const std::vector<std::string> trace = draw_trace(f, 8);
    RC_ASSERT(satisfied(c, trace) == satisfied(f, trace));
  }
}

}  // namespace
}  // namespace rondo::ltl
