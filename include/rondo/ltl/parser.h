// Reads a co-safe LTL formula over map nodes from text, refusing whatever lies outside the
// fragment with the 1-based character position and the reason (docs/ltl.md has the grammar).
//
//   Result<Formula> f = parse_formula("F WayPoint3 & (!Kitchen U (WayPoint5 | WayPoint9))");
//   Result<Formula> g = parse_formula("G WayPoint1");
//   // g.error().message: "position 1: 'G' (always) is outside the co-safe fragment: ..."
//
// Precedence, loosest first: '->' (right), '|', '&', 'U' (right), then the prefixes '!', 'X',
// 'F'. Node names are bare (a letter or '_', then letters, digits, '_') or double-quoted with
// \" and \\ escapes ("Room 1.2", "X" for a node named like an operator).
#pragma once

#include <cstddef>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/ltl/formula.h"

namespace rondo::ltl {

struct ParseOptions {
  std::size_t max_bytes = 4096;  // longer text is refused before it is read
  std::size_t max_depth = 64;    // nesting of operators and parentheses
};

// The formula, or an error (kInvalidInput) whose message starts "position N: " (N counts
// characters from 1) and says what is wrong there. `a -> b` is read as `!a | b` when a is a node
// or a negated node; any other left side is refused (its negation would not be co-safe).
Result<Formula> parse_formula(std::string_view text, const ParseOptions& options = {});

}  // namespace rondo::ltl
