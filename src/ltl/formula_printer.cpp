// to_string(Formula): the parser's syntax with the fewest parentheses its precedence allows.
#include <string_view>

#include "characters.h"
#include "rondo/ltl/formula.h"

namespace rondo::ltl {

namespace {

// Binding strength, loosest first; an operand looser than its context gets parentheses.
enum Level : int { kOrLevel = 1, kAndLevel = 2, kUntilLevel = 3, kUnaryLevel = 4, kAtomLevel = 5 };

int level_of(const Formula& f) {
  switch (f.op()) {
    case Op::kOr: return kOrLevel;
    case Op::kAnd: return kAndLevel;
    case Op::kUntil: return kUntilLevel;
    case Op::kNext:
    case Op::kEventually:
    case Op::kNotAt: return kUnaryLevel;
    default: return kAtomLevel;
  }
}

void print_node_name(const std::string& name, std::string& out) {
  if (is_bare_node_name(name)) {
    out += name;
    return;
  }
  out += '"';
  for (char c : name) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  out += '"';
}

void print(const Formula& f, int context, std::string& out);

void print_list(const Formula& f, std::string_view separator, int operand_level, std::string& out) {
  bool first = true;
  for (const Formula& g : f.operands()) {
    if (!first) out += separator;
    first = false;
    print(g, operand_level, out);
  }
}

// Prints `f` where an operand of binding strength at least `context` is expected.
void print(const Formula& f, int context, std::string& out) {
  const bool parenthesise = level_of(f) < context;
  if (parenthesise) out += '(';
  switch (f.op()) {
    case Op::kTrue: out += "true"; break;
    case Op::kFalse: out += "false"; break;
    case Op::kAt: print_node_name(f.node(), out); break;
    case Op::kNotAt:
      out += '!';
      print_node_name(f.node(), out);
      break;
    case Op::kNext:
    case Op::kEventually:
      out += f.op() == Op::kNext ? "X " : "F ";
      print(f.operand(0), kUnaryLevel, out);
      break;
    case Op::kUntil:  // right-associative: a U b U c is a U (b U c)
      print(f.operand(0), kUnaryLevel, out);
      out += " U ";
      print(f.operand(1), kUntilLevel, out);
      break;
    // Operands of a conjunction are never conjunctions (all_of splices them), and the same for
    // disjunctions, so the next level up is enough.
    case Op::kAnd: print_list(f, " & ", kUntilLevel, out); break;
    case Op::kOr: print_list(f, " | ", kAndLevel, out); break;
  }
  if (parenthesise) out += ')';
}

}  // namespace

bool is_bare_node_name(std::string_view name) {
  if (name.empty() || !is_name_start(name.front())) return false;
  for (char c : name)
    if (!is_name_char(c)) return false;
  for (std::string_view word : kReservedWords)
    if (name == word) return false;
  return true;
}

std::string to_string(const Formula& formula) {
  std::string out;
  print(formula, kOrLevel, out);
  return out;
}

}  // namespace rondo::ltl
