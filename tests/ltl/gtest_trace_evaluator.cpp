// The direct evaluator on finite traces: the semantics of docs/ltl.md, case by case.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rondo/ltl/parser.h"
#include "rondo/ltl/trace_evaluator.h"

namespace rondo::ltl {
namespace {

struct Case {
  std::string formula;
  std::vector<std::string> trace;
  bool satisfied;
};

TEST(TraceEvaluator, FollowsTheFiniteTraceSemantics) {
  const std::vector<Case> cases = {
      {"a", {"a"}, true},
      {"a", {"b", "a"}, false},
      {"a", {}, false},
      {"!a", {"b"}, true},
      {"!a", {}, false},  // at the end no proposition holds, negated or not
      {"true", {}, true},
      {"F true", {}, true},
      {"X true", {}, false},
      {"X true", {"a"}, true},  // one node was reached after the first: the end is a next position
      {"X a", {"b", "a"}, true},
      {"X a", {"b"}, false},
      {"X (a | !a)", {"b"}, false},  // needs a node after the first
      {"X (a | !a)", {"b", "c"}, true},
      {"F a", {"b", "c", "a"}, true},
      {"F a", {"b", "c"}, false},
      {"F a & F b", {"b", "c", "a"}, true},
      {"F (a & F b)", {"b", "a", "c"}, false},
      {"F (a & F b)", {"a", "b"}, true},
      {"F (a & X b)", {"a", "c", "b"}, false},
      {"!d U s", {"a", "b", "s"}, true},
      {"!d U s", {"a", "d", "s"}, false},
      {"!d U s", {"a", "b"}, false},
      {"!d U s", {"s", "d"}, true},  // done before d
      {"!k U (e & (!k U w))", {"x", "e", "y", "w"}, true},
      {"!k U (e & (!k U w))", {"x", "e", "k", "w"}, false},
      {"!k U (e & (!k U w))", {"x", "k", "e", "w"}, false},
  };
  for (const Case& c : cases) {
    const Formula f = parse_formula(c.formula).value();
    EXPECT_EQ(satisfied(f, c.trace), c.satisfied) << c.formula << " on " << ::testing::PrintToString(c.trace);
  }
}

}  // namespace
}  // namespace rondo::ltl
