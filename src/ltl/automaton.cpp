// Automaton::build: breadth-first exploration of the progressed formulas, under the size limits,
// then minimisation (minimise.h).
#include "rondo/ltl/automaton.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

#include "minimise.h"
#include "rondo/ltl/progression.h"

namespace rondo::ltl {

namespace {

struct Exploration {
  std::vector<Formula> states;
  TransitionTable table;
};

Result<Exploration> explore(const Formula& start, std::span<const std::string> nodes, const AutomatonOptions& o) {
  Exploration x;
  x.table.letters = nodes.size() + 1;
  std::map<Formula, std::uint32_t> index;
  auto add = [&](Formula f) -> Result<std::uint32_t> {
    if (auto it = index.find(f); it != index.end()) return it->second;
    if (x.states.size() >= o.max_states)
      return Error::invalid(fmt::format(
          "the formula's automaton would have more than {} states (the limit): split the task into smaller ones",
          o.max_states));
    if (f.size() > o.max_formula_size)
      return Error::invalid(fmt::format("a progressed formula has more than {} operators and nodes (the limit)",
                                        o.max_formula_size));
    const auto q = static_cast<std::uint32_t>(x.states.size());
    index.emplace(f, q);
    x.states.push_back(std::move(f));
    return q;
  };
  RONDO_RETURN_IF_ERROR(add(start));
  for (std::size_t q = 0; q < x.states.size(); ++q) {
    for (std::size_t a = 0; a < x.table.letters; ++a) {
      const std::optional<std::string_view> node =
          a < nodes.size() ? std::optional<std::string_view>(nodes[a]) : std::nullopt;
      RONDO_ASSIGN_OR_RETURN(std::uint32_t to, add(progress(x.states[q], node)));
      x.table.delta.push_back(to);
    }
    x.table.accepting.push_back(x.states[q].op() == Op::kTrue);
  }
  return x;
}

// The simplest formula of each class: fewest operators, then the first in the formulas' order.
std::vector<Formula> representatives(const std::vector<Formula>& states, const std::vector<std::uint32_t>& cls,
                                     std::size_t count) {
  std::vector<std::optional<Formula>> best(count);
  for (std::size_t q = 0; q < states.size(); ++q) {
    std::optional<Formula>& b = best[cls[q]];
    const Formula& f = states[q];
    if (!b || f.size() < b->size() || (f.size() == b->size() && f < *b)) b = f;
  }
  std::vector<Formula> out;
  for (auto& b : best) out.push_back(std::move(*b));
  return out;
}

}  // namespace

Result<Automaton> Automaton::build(const Formula& formula, const AutomatonOptions& options) {
  if (formula.depth() > options.max_depth)
    return Error::invalid(fmt::format("the formula nests deeper than {} levels (the limit)", options.max_depth));
  Automaton a;
  a.nodes_ = named_nodes(formula);
  a.formula_ = canonical(formula);
  RONDO_ASSIGN_OR_RETURN(Exploration x, explore(a.formula_, a.nodes_, options));
  a.explored_ = x.states.size();
  std::vector<std::uint32_t> cls(x.states.size());
  for (std::size_t q = 0; q < cls.size(); ++q) cls[q] = static_cast<std::uint32_t>(q);
  if (options.minimise) cls = equivalence_classes(x.table);
  const std::size_t count = cls.empty() ? 0 : *std::max_element(cls.begin(), cls.end()) + 1;
  const std::size_t letters = x.table.letters;
  a.delta_.assign(count * letters, 0);
  a.accepting_.assign(count, 0);
  for (std::size_t q = 0; q < x.states.size(); ++q) {
    for (std::size_t l = 0; l < letters; ++l) a.delta_[cls[q] * letters + l] = cls[x.table.delta[q * letters + l]];
    a.accepting_[cls[q]] = x.table.accepting[q];
  }
  a.obligations_ = representatives(x.states, cls, count);
  a.find_rejecting();
  return a;
}

// Rejecting: the states from which no accepting state can be reached (a backward search).
void Automaton::find_rejecting() {
  const std::size_t n = state_count(), letters = letter_count();
  std::vector<char> live = accepting_;
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t q = 0; q < n; ++q) {
      if (live[q]) continue;
      for (std::size_t l = 0; l < letters && !live[q]; ++l) live[q] = live[delta_[q * letters + l]];
      changed = changed || live[q];
    }
  }
  rejecting_.assign(n, 0);
  for (std::size_t q = 0; q < n; ++q) rejecting_[q] = !live[q];
}

Automaton::Letter Automaton::letter_of(std::string_view node) const {
  const auto it = std::lower_bound(nodes_.begin(), nodes_.end(), node);
  if (it == nodes_.end() || *it != node) return other_letter();
  return static_cast<Letter>(it - nodes_.begin());
}

bool Automaton::accepts(std::span<const std::string> trace) const {
  State q = initial();
  for (const std::string& node : trace) q = next(q, node);
  return accepting(q);
}

}  // namespace rondo::ltl
