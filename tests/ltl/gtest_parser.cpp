// The formula parser and printer: precedence and associativity, quoted names, what is refused
// outside the fragment (with the 1-based character position), and the input limits.
#include <gtest/gtest.h>

#include <string>

#include "rondo/ltl/parser.h"

namespace rondo::ltl {
namespace {

Formula at(const std::string& n) { return Formula::at(n); }

struct Reading {
  std::string text;
  Formula expected;
};

TEST(Parser, PrecedenceAndAssociativity) {
  const Formula a = at("a"), b = at("b"), c = at("c");
  const std::vector<Reading> cases = {
      {"a | b & c", Formula::any_of({a, Formula::all_of({b, c})})},
      {"a & b | c", Formula::any_of({Formula::all_of({a, b}), c})},
      {"a U b & c", Formula::all_of({Formula::until(a, b), c})},
      {"a U b U c", Formula::until(a, Formula::until(b, c))},
      {"(a U b) U c", Formula::until(Formula::until(a, b), c)},
      {"F a U b", Formula::until(Formula::eventually(a), b)},
      {"!a U X b", Formula::until(Formula::not_at("a"), Formula::next(b))},
      {"X F !a", Formula::next(Formula::eventually(Formula::not_at("a")))},
      {"a & (b & c)", Formula::all_of({a, b, c})},
      {"(a | b) | c", Formula::any_of({a, b, c})},
      {"a -> F b", Formula::any_of({Formula::not_at("a"), Formula::eventually(b)})},
      {"!a -> b | c", Formula::any_of({a, b, c})},
      {"a -> b -> c", Formula::any_of({Formula::not_at("a"), Formula::not_at("b"), c})},
      {"!(a)", Formula::not_at("a")},
      {"!true | !false", Formula::any_of({Formula::falsity(), Formula::truth()})},
      {"  F\tWayPoint5\n& F WayPoint7 ", Formula::all_of({Formula::eventually(at("WayPoint5")),
                                                           Formula::eventually(at("WayPoint7"))})},
  };
  for (const Reading& r : cases) {
    Result<Formula> f = parse_formula(r.text);
    ASSERT_TRUE(f.ok()) << r.text << ": " << f.error().message;
    EXPECT_EQ(*f, r.expected) << r.text << " read as " << to_string(*f);
  }
}

TEST(Parser, QuotedNamesHoldAnyCharacterAndPrintBack) {
  const std::vector<Reading> cases = {
      {"\"Room 1.2\"", at("Room 1.2")},
      {"F \"X\"", Formula::eventually(at("X"))},
      {"\"say \\\"hi\\\"\" & \"back\\\\slash\"", Formula::all_of({at("say \"hi\""), at("back\\slash")})},
      {"!\"café\"", Formula::not_at("café")},
      {"\"true\" U \"G\"", Formula::until(at("true"), at("G"))},
  };
  for (const Reading& r : cases) {
    Result<Formula> f = parse_formula(r.text);
    ASSERT_TRUE(f.ok()) << r.text << ": " << f.error().message;
    EXPECT_EQ(*f, r.expected) << r.text;
    EXPECT_EQ(parse_formula(to_string(*f)).value(), *f) << to_string(*f);
  }
}

TEST(Printer, UsesTheFewestParentheses) {
  const Formula a = at("a"), b = at("b"), c = at("c");
  EXPECT_EQ(to_string(Formula::any_of({a, Formula::all_of({b, c})})), "a | b & c");
  EXPECT_EQ(to_string(Formula::all_of({Formula::any_of({a, b}), c})), "(a | b) & c");
  EXPECT_EQ(to_string(Formula::until(Formula::until(a, b), c)), "(a U b) U c");
  EXPECT_EQ(to_string(Formula::until(a, Formula::until(b, c))), "a U b U c");
  EXPECT_EQ(to_string(Formula::eventually(Formula::all_of({a, Formula::eventually(b)}))), "F (a & F b)");
  EXPECT_EQ(to_string(Formula::all_of({Formula::not_at("Room 1"), at("U")})), "!\"Room 1\" & \"U\"");
}

struct Refusal {
  std::string text;
  std::string message_start;  // "position N: ..." up to the reason's first words
};

TEST(Parser, RefusesWhatIsOutsideTheFragmentNamingThePosition) {
  const std::vector<Refusal> cases = {
      {"G a", "position 1: 'G' (always) is outside the co-safe fragment"},
      {"F a & G !b", "position 7: 'G' (always)"},
      {"a R b", "position 3: 'R' (release) is outside"},
      {"a W b", "position 3: 'W' (weak until)"},
      {"a M b", "position 3: 'M' (strong release) is not supported"},
      {"a <-> F b", "position 3: '<->' is outside the co-safe fragment"},
      {"!F a", "position 1: '!' applies to a node only, here to an 'F' formula"},
      {"F !(a U b)", "position 3: '!' applies to a node only, here to a 'U' formula"},
      {"!(a & b)", "position 1: '!' applies to a node only, here to a '&' formula: push it inwards"},
      {"!(a | b)", "position 1: '!' applies to a node only, here to a '|' formula"},
      {"!X a", "position 1: '!' applies to a node only, here to an 'X' formula"},
      {"!!a", "position 1: '!' applies to a node only, here to a negated node"},
      {"F a -> b", "position 5: the left side of '->' must be a node or a negated node"},
      {"(a | b) -> c", "position 9: the left side of '->'"},
      {"\"café\" & G b", "position 10: 'G'"},  // positions count characters, not bytes
  };
  for (const Refusal& r : cases) {
    Result<Formula> f = parse_formula(r.text);
    ASSERT_FALSE(f.ok()) << r.text;
    EXPECT_EQ(f.error().code, ErrorCode::kInvalidInput);
    EXPECT_TRUE(f.error().message.starts_with(r.message_start)) << r.text << "\n  got: " << f.error().message;
  }
}

TEST(Parser, RefusesMalformedTextNamingThePosition) {
  const std::vector<Refusal> cases = {
      {"", "position 1: expected a node, 'true', 'false', '(', '!', 'X' or 'F', found the end of the formula"},
      {"F", "position 2: expected a node"},
      {"a &", "position 4: expected a node"},
      {"a & & b", "position 5: expected a node, 'true', 'false', '(', '!', 'X' or 'F', found '&'"},
      {"(a | b", "position 7: expected ')' to close the '(' at position 1, found the end of the formula"},
      {"a b", "position 3: expected an operator or the end of the formula, found node 'b'"},
      {"a )", "position 3: expected an operator or the end of the formula, found ')'"},
      {"a # b", "position 3: unexpected character '#'"},
      {"a - b", "position 3: unexpected character '-'"},
      {"a & \"open", "position 5: the quoted node name that starts here is not closed"},
      {"\"\"", "position 1: an empty node name"},
      {"\"a\tb\"", "position 3: a control character in a quoted node name"},
      {"a & \xff", "position 5: the formula is not valid UTF-8 here"},
  };
  for (const Refusal& r : cases) {
    Result<Formula> f = parse_formula(r.text);
    ASSERT_FALSE(f.ok()) << r.text;
    EXPECT_TRUE(f.error().message.starts_with(r.message_start)) << r.text << "\n  got: " << f.error().message;
  }
}

TEST(Parser, RefusesInputBeyondItsLimitsWithoutRecursingDeeply) {
  EXPECT_EQ(parse_formula(std::string(5000, 'a')).error().message,
            "the formula is 5000 bytes long, more than the limit of 4096");
  // 4,000 nested parentheses or prefixes: refused at the 65th level, not a stack overflow.
  const Result<Formula> parens = parse_formula(std::string(4000, '(') + "a");
  EXPECT_EQ(parens.error().message, "position 65: the formula nests deeper than 64 levels");
  std::string prefixes;
  for (int i = 0; i < 2000; ++i) prefixes += "!F";
  EXPECT_EQ(parse_formula(prefixes + "a").error().message, "position 65: the formula nests deeper than 64 levels");
  std::string chain;
  for (int i = 0; i < 100; ++i) chain += "X ";
  EXPECT_TRUE(parse_formula(chain + "a", {.max_depth = 100}).ok());
  EXPECT_FALSE(parse_formula(chain + "a", {.max_depth = 99}).ok());
  EXPECT_TRUE(parse_formula(std::string(60, '(') + "a" + std::string(60, ')')).ok());
}

}  // namespace
}  // namespace rondo::ltl
