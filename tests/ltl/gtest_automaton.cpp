// The automaton of the issue's example formulas (sizes, accepted and refused traces), the
// rejecting sink, letters, and the size limit.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rondo/ltl/automaton.h"
#include "rondo/ltl/parser.h"

namespace rondo::ltl {
namespace {

using Trace = std::vector<std::string>;

Automaton automaton_of(const std::string& text, const AutomatonOptions& options = {}) {
  return Automaton::build(parse_formula(text).value(), options).value();
}

struct Example {
  std::string words;
  std::string formula;
  std::size_t states;
  std::vector<Trace> accepted;
  std::vector<Trace> refused;
};

TEST(Automaton, TheIssueExamples) {
  const std::vector<Example> examples = {
      {"visit WayPoint5 and WayPoint7, in any order", "F WayPoint5 & F WayPoint7", 4,
       {{"WayPoint1", "WayPoint7", "WayPoint2", "WayPoint5"}, {"WayPoint5", "WayPoint7"}},
       {{"WayPoint5"}, {"WayPoint7", "WayPoint7"}, {}}},
      {"go to WayPoint3, then to WayPoint5 or WayPoint9", "F (WayPoint3 & F (WayPoint5 | WayPoint9))", 3,
       {{"WayPoint3", "WayPoint9"}, {"WayPoint5", "WayPoint3", "WayPoint1", "WayPoint5"}},
       {{"WayPoint9", "WayPoint3"}, {"WayPoint3"}}},
      {"reach the Station without passing WayPoint12", "!WayPoint12 U Station", 3,
       {{"WayPoint1", "Station"}, {"Station", "WayPoint12"}},
       {{"WayPoint1", "WayPoint12", "Station"}, {"WayPoint12"}, {"WayPoint1"}}},
      {"check the east fire door, then the west one, never crossing the kitchen corridor",
       "!Kitchen U (EastDoor & (!Kitchen U WestDoor))", 4,
       {{"Hall", "EastDoor", "Hall", "WestDoor"}, {"EastDoor", "WestDoor", "Kitchen"}},
       {{"Hall", "WestDoor", "EastDoor"}, {"EastDoor", "Kitchen", "WestDoor"}, {"Kitchen", "EastDoor", "WestDoor"}}},
  };
  for (const Example& e : examples) {
    SCOPED_TRACE(e.words);
    const Automaton a = automaton_of(e.formula);
    EXPECT_EQ(a.state_count(), e.states);
    for (const Trace& t : e.accepted) EXPECT_TRUE(a.accepts(t)) << ::testing::PrintToString(t);
    for (const Trace& t : e.refused) EXPECT_FALSE(a.accepts(t)) << ::testing::PrintToString(t);
  }
}

TEST(Automaton, StatesAreWhatRemainsToDo) {
  const Automaton a = automaton_of("F A & F B");
  EXPECT_EQ(a.letter_count(), 3u);
  EXPECT_EQ(a.letter_of("B"), 1u);
  EXPECT_EQ(a.letter_of("Kitchen"), a.other_letter());
  const Automaton::State start = a.next(a.initial(), "Station");
  EXPECT_EQ(start, a.initial());
  EXPECT_EQ(to_string(a.obligation(a.next(start, "A"))), "F B");
  const Automaton::State done = a.next(a.next(start, "A"), "B");
  EXPECT_TRUE(a.accepting(done));
  EXPECT_EQ(a.obligation(done), Formula::truth());
  for (Automaton::Letter l = 0; l < a.letter_count(); ++l) EXPECT_EQ(a.next(done, l), done);  // stays done
  for (Automaton::State q = 0; q < a.state_count(); ++q) EXPECT_FALSE(a.rejecting(q));  // nothing to break
}

TEST(Automaton, AViolationEndsInTheOneRejectingSink) {
  const Automaton a = automaton_of("!d U (s & X (!d U t))");
  const Automaton::State q = a.next(a.initial(), "d");
  EXPECT_TRUE(a.rejecting(q));
  EXPECT_EQ(a.obligation(q), Formula::falsity());
  for (Automaton::Letter l = 0; l < a.letter_count(); ++l) EXPECT_EQ(a.next(q, l), q);
  std::size_t sinks = 0;
  for (Automaton::State s = 0; s < a.state_count(); ++s)
    if (a.rejecting(s)) ++sinks;
  EXPECT_EQ(sinks, 1u);
  // Unsatisfiable from the start: one node at a time.
  const Automaton never = automaton_of("F (a & b)");
  EXPECT_EQ(never.state_count(), 1u);
  EXPECT_TRUE(never.rejecting(never.initial()));
}

TEST(Automaton, MinimisingMergesEquivalentObligations) {
  // "X F a | F a" is "F a", which the canonical form does not see; after another node it is "F a".
  const Formula f = parse_formula("X F a | F a").value();
  const Automaton full = Automaton::build(f, {.minimise = false}).value();
  const Automaton small = Automaton::build(f).value();
  EXPECT_EQ(full.state_count(), 3u);
  EXPECT_EQ(small.state_count(), 2u);
  EXPECT_EQ(small.explored_states(), 3u);
  EXPECT_EQ(to_string(small.obligation(small.initial())), "F a");  // the simplest of its class
}

TEST(Automaton, RefusesAFormulaWhoseAutomatonPassesTheLimit) {
  // Visiting n places in any order needs 2^n states.
  std::string visit_all = "F p0";
  for (int i = 1; i < 9; ++i) visit_all += " & F p" + std::to_string(i);
  const Result<Automaton> a = Automaton::build(parse_formula(visit_all).value());
  ASSERT_FALSE(a.ok());
  EXPECT_EQ(a.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(a.error().message,
            "the formula's automaton would have more than 256 states (the limit): split the task into smaller ones");
  EXPECT_EQ(Automaton::build(parse_formula(visit_all).value(), {.max_states = 512})->state_count(), 512u);
  std::string eight = "F p0";
  for (int i = 1; i < 8; ++i) eight += " & F p" + std::to_string(i);
  EXPECT_EQ(automaton_of(eight).state_count(), 256u);
}

TEST(Automaton, RefusesAFormulaNestedBeyondTheLimit) {
  Formula deep = Formula::at("a");
  for (int i = 0; i < 200; ++i) deep = Formula::next(deep);
  EXPECT_EQ(Automaton::build(deep).error().message, "the formula nests deeper than 128 levels (the limit)");
  EXPECT_TRUE(Automaton::build(deep, {.max_depth = 201}).ok());
}

}  // namespace
}  // namespace rondo::ltl
