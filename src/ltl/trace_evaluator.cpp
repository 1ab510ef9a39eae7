// One truth vector over the positions 0 … n per subformula, filled from the end backwards.
#include "rondo/ltl/trace_evaluator.h"

#include <vector>

namespace rondo::ltl {

namespace {

using Truth = std::vector<char>;  // one entry per position 0 … n

Truth evaluate(const Formula& f, std::span<const std::string> w) {
  const std::size_t n = w.size();
  Truth v(n + 1, 0);
  switch (f.op()) {
    case Op::kTrue: v.assign(n + 1, 1); break;
    case Op::kFalse: break;
    case Op::kAt:
    case Op::kNotAt:
      for (std::size_t i = 0; i < n; ++i) v[i] = (w[i] == f.node()) == (f.op() == Op::kAt);
      break;
    case Op::kAnd:
    case Op::kOr: {
      const bool conjunction = f.op() == Op::kAnd;
      v.assign(n + 1, conjunction ? 1 : 0);
      for (const Formula& g : f.operands()) {
        const Truth u = evaluate(g, w);
        for (std::size_t i = 0; i <= n; ++i) v[i] = conjunction ? (v[i] && u[i]) : (v[i] || u[i]);
      }
      break;
    }
    case Op::kNext: {
      const Truth u = evaluate(f.operand(0), w);
      for (std::size_t i = 0; i < n; ++i) v[i] = u[i + 1];
      break;
    }
    case Op::kEventually: {
      const Truth u = evaluate(f.operand(0), w);
      v[n] = u[n];
      for (std::size_t i = n; i-- > 0;) v[i] = u[i] || v[i + 1];
      break;
    }
    case Op::kUntil: {
      const Truth hold = evaluate(f.operand(0), w), reach = evaluate(f.operand(1), w);
      v[n] = reach[n];
      for (std::size_t i = n; i-- > 0;) v[i] = reach[i] || (hold[i] && v[i + 1]);
      break;
    }
  }
  return v;
}

}  // namespace

bool satisfied(const Formula& formula, std::span<const std::string> trace) {
  return evaluate(formula, trace)[0] != 0;
}

}  // namespace rondo::ltl
