// progress(): the classic progression rules (X f -> f, F f -> f' | F f, f U g -> g' | (f' & f U g))
// through the canonical constructors, so that a canonical formula progresses to a canonical one.
#include "rondo/ltl/progression.h"

#include <vector>

#include "canonical_form.h"

namespace rondo::ltl {

Formula progress(const Formula& formula, std::optional<std::string_view> node) {
  switch (formula.op()) {
    case Op::kTrue:
    case Op::kFalse: return formula;
    case Op::kAt: return node == formula.node() ? Formula::truth() : Formula::falsity();
    case Op::kNotAt: return node == formula.node() ? Formula::falsity() : Formula::truth();
    case Op::kNext: return formula.operand(0);
    case Op::kEventually: return canonical_or({progress(formula.operand(0), node), formula});
    case Op::kUntil:
      return canonical_or({progress(formula.operand(1), node),
                           canonical_and({progress(formula.operand(0), node), formula})});
    case Op::kAnd:
    case Op::kOr: {
      std::vector<Formula> operands;
      for (const Formula& f : formula.operands()) operands.push_back(progress(f, node));
      return formula.op() == Op::kAnd ? canonical_and(std::move(operands)) : canonical_or(std::move(operands));
    }
  }
  return formula;
}

}  // namespace rondo::ltl
