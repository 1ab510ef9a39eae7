// Properties of the parser on random formulas of the fragment (at most 4 operators deep, names
// that need quotes and UTF-8 among them): printing and parsing give back the same formula, and a
// construct outside the fragment put anywhere in a formula is refused at its position.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <string>
#include <vector>

#include "formula_generators.h"
#include "rondo/ltl/parser.h"

namespace rondo::ltl {
namespace {

using testing::draw_formula;

RC_GTEST_PROP(ParserProperties, ParsingThePrintedFormulaGivesItBack, ()) {
  const Formula f = draw_formula(4, testing::node_pool().size());
  const Result<Formula> g = parse_formula(to_string(f));
  RC_ASSERT(g.ok());
  RC_ASSERT(*g == f);
}

// 1-based character position of byte `offset` of `text` (UTF-8).
std::size_t position_of(const std::string& text, std::size_t offset) {
  std::size_t p = 1;
  for (std::size_t i = 0; i < offset; ++i) p += (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80;
  return p;
}

// A formula that neither '!' nor the left side of '->' accepts: anything but a node, a negated
// node or a constant.
Formula draw_compound() {
  const Formula f = draw_formula(2, testing::node_pool().size());
  if (f.operands().empty()) return Formula::eventually(f);
  return f;
}

RC_GTEST_PROP(ParserProperties, AConstructOutsideTheFragmentIsRefusedAtItsPosition, ()) {
  const Formula context = draw_formula(2, testing::node_pool().size());
  const Formula hole = Formula::at("HOLE");
  const std::vector<Formula> places = {Formula::all_of({context, hole}), Formula::any_of({hole, context}),
                                       Formula::until(context, hole),      Formula::until(hole, context),
                                       Formula::eventually(hole),          Formula::all_of({Formula::next(hole), context})};
  const Formula placed = testing::pick_from(places);
  std::string text = to_string(placed);
  const std::size_t at = text.find("HOLE");
  RC_ASSERT(at != std::string::npos);
  const std::string left = to_string(draw_compound()), right = to_string(draw_formula(2));
  std::string construct, operator_name;
  std::size_t operator_offset = 0;  // in `construct`
  switch (testing::pick(0, 5)) {
    case 0: construct = "(G (" + right + "))", operator_offset = 1, operator_name = "'G'"; break;
    case 1: construct = "(!(" + left + "))", operator_offset = 1, operator_name = "'!'"; break;
    case 2:
      construct = "(" + left + " -> " + right + ")", operator_offset = 2 + left.size(), operator_name = "'->'";
      break;
    case 3:
      construct = "(" + left + " R " + right + ")", operator_offset = 2 + left.size(), operator_name = "'R'";
      break;
    default:
      construct = "(" + left + " <-> " + right + ")", operator_offset = 2 + left.size(), operator_name = "'<->'";
      break;
  }
  text.replace(at, 4, construct);
  const Result<Formula> f = parse_formula(text);
  RC_ASSERT(!f.ok());
  const std::string expected = "position " + std::to_string(position_of(text, at + operator_offset)) + ": ";
  RC_ASSERT(f.error().message.starts_with(expected));
  RC_ASSERT(f.error().message.find(operator_name) != std::string::npos);
}

}  // namespace
}  // namespace rondo::ltl
