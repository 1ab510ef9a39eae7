// A formula of syntactically co-safe LTL over the nodes of a map (docs/ltl.md): the atomic
// proposition `at X` holds when the robot is at node X. Negation applies to propositions only
// (`not_at X`), so every formula is in negation normal form and built from true, false, node
// propositions, their negations, ∧, ∨, X (next), F (eventually) and U (until).
//
//   Formula f = Formula::all_of({Formula::eventually(Formula::at("WayPoint5")),
//                                Formula::eventually(Formula::at("WayPoint7"))});
//   std::string text = to_string(f);                       // "F WayPoint5 & F WayPoint7"
//   Result<Formula> g = parse_formula(text);               // parser.h; *g == f
//
// A Formula is an immutable value: copies share their tree, == compares structure, and <=> is a
// total order (used to put formulas in a canonical form, progression.h). all_of / any_of flatten
// nested conjunctions / disjunctions but keep the operands' order; they do not simplify.
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace rondo::ltl {

// In the order of the canonical form's sorting (progression.h).
enum class Op : std::uint8_t {
  kFalse,
  kTrue,
  kAt,          // the robot is at node(): a proposition
  kNotAt,       // the robot is not at node(): a negated proposition
  kNext,        // X operand(0)
  kEventually,  // F operand(0)
  kUntil,       // operand(0) U operand(1)
  kAnd,         // operands(), at least two
  kOr,          // operands(), at least two
};

class Formula {
 public:
  // `true`.
  Formula();

  static Formula truth();
  static Formula falsity();
  static Formula at(std::string node);
  static Formula not_at(std::string node);
  static Formula next(Formula operand);
  static Formula eventually(Formula operand);
  static Formula until(Formula hold, Formula reach);
  // Operands that are themselves conjunctions (disjunctions) are spliced in. No operand: true
  // (false); one: that operand.
  static Formula all_of(std::vector<Formula> operands);
  static Formula any_of(std::vector<Formula> operands);

  Op op() const;
  // The node of kAt / kNotAt; empty for the other operators.
  const std::string& node() const;
  std::span<const Formula> operands() const;
  // Precondition: i < operands().size().
  const Formula& operand(std::size_t i) const { return operands()[i]; }

  // Operators and propositions in the tree, counted as a tree (shared parts count each time).
  std::size_t size() const;
  // The longest chain from the root to a leaf: 1 for a proposition.
  std::size_t depth() const;

  friend bool operator==(const Formula& a, const Formula& b);
  friend std::strong_ordering operator<=>(const Formula& a, const Formula& b);

 private:
  struct Tree;
  explicit Formula(std::shared_ptr<const Tree> tree) : tree_(std::move(tree)) {}
  static Formula make(Op op, std::string node, std::vector<Formula> operands);
  std::shared_ptr<const Tree> tree_;
};

// The formula in the parser's syntax (parser.h), with as few parentheses as the precedence
// allows and node names quoted where they need it: parse_formula(to_string(f)) == f.
std::string to_string(const Formula& formula);

// The nodes the formula names, sorted, each once.
std::vector<std::string> named_nodes(const Formula& formula);

// Whether `name` can be written without quotes: a letter or '_' followed by letters, digits and
// '_', and not one of the reserved words (X F U G R W M true false).
bool is_bare_node_name(std::string_view name);

}  // namespace rondo::ltl
