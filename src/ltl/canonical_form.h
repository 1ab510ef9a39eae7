// The constructors of the canonical form (progression.h): each takes canonical operands and
// returns the canonical formula of the operator applied to them.
#pragma once

#include <vector>

#include "rondo/ltl/formula.h"

namespace rondo::ltl {

Formula canonical_next(Formula operand);
Formula canonical_eventually(Formula operand);
Formula canonical_until(Formula hold, Formula reach);
Formula canonical_and(std::vector<Formula> operands);
Formula canonical_or(std::vector<Formula> operands);

}  // namespace rondo::ltl
