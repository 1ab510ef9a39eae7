#include "rondo/ltl/formula.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace rondo::ltl {

struct Formula::Tree {
  Op op;
  std::string node;
  std::vector<Formula> operands;
  std::size_t size;
  std::size_t depth;
};

Formula Formula::make(Op op, std::string node, std::vector<Formula> operands) {
  std::size_t size = 1, depth = 0;
  for (const Formula& f : operands) {
    size += f.size();
    depth = std::max(depth, f.depth());
  }
  return Formula(std::make_shared<const Tree>(Tree{op, std::move(node), std::move(operands), size, depth + 1}));
}

namespace {

// Splices operands of the same operator into `out`, keeping their order.
void splice(Op op, std::vector<Formula>& operands, std::vector<Formula>& out) {
  for (Formula& f : operands) {
    if (f.op() == op)
      out.insert(out.end(), f.operands().begin(), f.operands().end());
    else
      out.push_back(std::move(f));
  }
}

}  // namespace

Formula::Formula() : Formula(truth()) {}

Formula Formula::truth() {
  static const Formula t = make(Op::kTrue, {}, {});
  return t;
}
Formula Formula::falsity() {
  static const Formula f = make(Op::kFalse, {}, {});
  return f;
}
Formula Formula::at(std::string node) { return make(Op::kAt, std::move(node), {}); }
Formula Formula::not_at(std::string node) { return make(Op::kNotAt, std::move(node), {}); }
Formula Formula::next(Formula operand) { return make(Op::kNext, {}, {std::move(operand)}); }
Formula Formula::eventually(Formula operand) { return make(Op::kEventually, {}, {std::move(operand)}); }
Formula Formula::until(Formula hold, Formula reach) {
  return make(Op::kUntil, {}, {std::move(hold), std::move(reach)});
}

Formula Formula::all_of(std::vector<Formula> operands) {
  std::vector<Formula> flat;
  splice(Op::kAnd, operands, flat);
  if (flat.empty()) return truth();
  if (flat.size() == 1) return std::move(flat.front());
  return make(Op::kAnd, {}, std::move(flat));
}

Formula Formula::any_of(std::vector<Formula> operands) {
  std::vector<Formula> flat;
  splice(Op::kOr, operands, flat);
  if (flat.empty()) return falsity();
  if (flat.size() == 1) return std::move(flat.front());
  return make(Op::kOr, {}, std::move(flat));
}

Op Formula::op() const { return tree_->op; }
const std::string& Formula::node() const { return tree_->node; }
std::span<const Formula> Formula::operands() const { return tree_->operands; }
std::size_t Formula::size() const { return tree_->size; }
std::size_t Formula::depth() const { return tree_->depth; }

bool operator==(const Formula& a, const Formula& b) { return (a <=> b) == std::strong_ordering::equal; }

std::strong_ordering operator<=>(const Formula& a, const Formula& b) {
  if (a.tree_ == b.tree_) return std::strong_ordering::equal;
  if (auto c = a.op() <=> b.op(); c != 0) return c;
  if (auto c = a.node() <=> b.node(); c != 0) return c;
  const auto x = a.operands(), y = b.operands();
  if (auto c = x.size() <=> y.size(); c != 0) return c;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (auto c = x[i] <=> y[i]; c != 0) return c;
  return std::strong_ordering::equal;
}

namespace {

void collect_nodes(const Formula& f, std::vector<std::string>& out) {
  if (f.op() == Op::kAt || f.op() == Op::kNotAt) out.push_back(f.node());
  for (const Formula& g : f.operands()) collect_nodes(g, out);
}

}  // namespace

std::vector<std::string> named_nodes(const Formula& formula) {
  std::vector<std::string> out;
  collect_nodes(formula, out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace rondo::ltl
