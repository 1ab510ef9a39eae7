// The canonical form's rules (progression.h lists them). Each rule is an equivalence on every
// finite trace, the empty one included, where no proposition holds (docs/ltl.md proves the
// one-node-at-a-time rules).
//
// Conjunctions and disjunctions are kept in disjunctive normal form over *atoms* (propositions,
// their negations and X / F / U formulas), with subsumed conjunctions dropped. Progression only
// ever creates atoms that are subformulas of the formula it started from, so the canonical
// formulas it reaches are finitely many (sets of sets of those atoms): the automaton's
// construction always ends, and the state limit only bounds its size. When distributing would
// make more than kMaxConjunctions conjunctions, the disjunctions are kept whole as atoms instead
// (still equivalent, no longer normal; the automaton's limits then bound the work).
#include "canonical_form.h"

#include <algorithm>
#include <iterator>
#include <optional>
#include <string>
#include <utility>

#include "rondo/ltl/progression.h"

namespace rondo::ltl {

namespace {

constexpr std::size_t kMaxConjunctions = 256;

using Conjunction = std::vector<Formula>;  // sorted atoms, no repeats; empty: true
using Dnf = std::vector<Conjunction>;      // sorted, no conjunction implies another; empty: false

Conjunction conjunction_of(const Formula& f) {
  if (f.op() == Op::kTrue) return {};
  if (f.op() == Op::kAnd) return {f.operands().begin(), f.operands().end()};
  return {f};
}

Dnf dnf_of(const Formula& f) {
  if (f.op() == Op::kFalse) return {};
  if (f.op() != Op::kOr) return {conjunction_of(f)};
  Dnf out;
  for (const Formula& g : f.operands()) out.push_back(conjunction_of(g));
  return out;
}

Formula formula_of(const Dnf& dnf) {
  std::vector<Formula> terms;
  for (const Conjunction& c : dnf) terms.push_back(Formula::all_of(c));
  return Formula::any_of(std::move(terms));
}

// The robot is at one node at a time: two nodes never hold together, a node excludes its own
// negation and implies the negation of any other. Nothing when the conjunction is false.
std::optional<Conjunction> one_node_at_a_time(Conjunction c) {
  const Formula* here = nullptr;
  for (const Formula& f : c) {
    if (f.op() != Op::kAt) continue;
    if (here) return std::nullopt;  // two different nodes (no repeats in a conjunction)
    here = &f;
  }
  if (!here) return c;
  const std::string node = here->node();
  for (const Formula& f : c)
    if (f.op() == Op::kNotAt && f.node() == node) return std::nullopt;
  std::erase_if(c, [](const Formula& f) { return f.op() == Op::kNotAt; });
  return c;
}

bool atom_implied_by(const Formula& atom, const Conjunction& c) {
  if (std::binary_search(c.begin(), c.end(), atom)) return true;
  if (atom.op() != Op::kNotAt) return false;
  return std::any_of(c.begin(), c.end(), [&](const Formula& f) { return f.op() == Op::kAt && f.node() != atom.node(); });
}

// Whether every atom of `weaker` follows from `stronger` (then stronger | weaker = weaker).
bool implies(const Conjunction& stronger, const Conjunction& weaker) {
  return std::all_of(weaker.begin(), weaker.end(), [&](const Formula& a) { return atom_implied_by(a, stronger); });
}

// Sorted, without repeats, and without conjunctions that imply another one.
Dnf normalise(Dnf dnf) {
  std::sort(dnf.begin(), dnf.end());
  dnf.erase(std::unique(dnf.begin(), dnf.end()), dnf.end());
  std::vector<char> redundant(dnf.size(), 0);
  for (std::size_t i = 0; i < dnf.size(); ++i)
    // i goes when it implies another conjunction; of two that imply each other, the later goes.
    for (std::size_t j = 0; j < dnf.size() && !redundant[i]; ++j)
      redundant[i] = j != i && implies(dnf[i], dnf[j]) && (j < i || !implies(dnf[j], dnf[i]));
  Dnf out;
  for (std::size_t i = 0; i < dnf.size(); ++i)
    if (!redundant[i]) out.push_back(std::move(dnf[i]));
  return out;
}

Conjunction merge(const Conjunction& a, const Conjunction& b) {
  Conjunction out;
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(out));
  return out;
}

// The conjunction of the DNFs, distributed; when that would pass kMaxConjunctions, the
// disjunctions stay whole, as atoms of one conjunction.
Dnf conjoin(const std::vector<Dnf>& parts) {
  std::size_t product = 1;
  for (const Dnf& d : parts) product = d.empty() ? 0 : std::min(product * d.size(), kMaxConjunctions + 1);
  if (product > kMaxConjunctions) {
    Conjunction atoms;
    for (const Dnf& d : parts) atoms = merge(atoms, d.size() == 1 ? d.front() : Conjunction{formula_of(d)});
    if (auto c = one_node_at_a_time(std::move(atoms))) return {std::move(*c)};
    return {};
  }
  Dnf acc = {Conjunction{}};
  for (const Dnf& d : parts) {
    Dnf next;
    for (const Conjunction& a : acc)
      for (const Conjunction& b : d)
        if (auto c = one_node_at_a_time(merge(a, b))) next.push_back(std::move(*c));
    acc = normalise(std::move(next));
  }
  return acc;
}

}  // namespace

Formula canonical_next(Formula operand) {
  if (operand.op() == Op::kFalse) return operand;
  return Formula::next(std::move(operand));
}

Formula canonical_eventually(Formula operand) {
  switch (operand.op()) {
    case Op::kTrue:
    case Op::kFalse:
    case Op::kEventually: return operand;
    default: return Formula::eventually(std::move(operand));
  }
}

Formula canonical_until(Formula hold, Formula reach) {
  if (reach.op() == Op::kTrue || reach.op() == Op::kFalse || hold.op() == Op::kFalse || hold == reach) return reach;
  if (hold.op() == Op::kTrue) return canonical_eventually(std::move(reach));
  return Formula::until(std::move(hold), std::move(reach));
}

Formula canonical_and(std::vector<Formula> operands) {
  std::vector<Dnf> parts;
  for (const Formula& f : operands) parts.push_back(dnf_of(f));
  return formula_of(conjoin(parts));
}

Formula canonical_or(std::vector<Formula> operands) {
  Dnf all;
  for (const Formula& f : operands)
    for (Conjunction& c : dnf_of(f)) all.push_back(std::move(c));
  return formula_of(normalise(std::move(all)));
}

Formula canonical(const Formula& formula) {
  std::vector<Formula> operands;
  for (const Formula& f : formula.operands()) operands.push_back(canonical(f));
  switch (formula.op()) {
    case Op::kNext: return canonical_next(std::move(operands[0]));
    case Op::kEventually: return canonical_eventually(std::move(operands[0]));
    case Op::kUntil: return canonical_until(std::move(operands[0]), std::move(operands[1]));
    case Op::kAnd: return canonical_and(std::move(operands));
    case Op::kOr: return canonical_or(std::move(operands));
    default: return formula;
  }
}

}  // namespace rondo::ltl
