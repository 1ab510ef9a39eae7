#include "minimise.h"

#include <map>

namespace rondo::ltl {

namespace {

// One refinement round: states with the same class and the same successor classes stay together.
std::vector<std::uint32_t> refine(const TransitionTable& t, const std::vector<std::uint32_t>& cls, std::size_t& count) {
  std::map<std::vector<std::uint32_t>, std::uint32_t> ids;
  std::vector<std::uint32_t> out(t.state_count());
  std::vector<std::uint32_t> signature(t.letters + 1);
  for (std::size_t q = 0; q < t.state_count(); ++q) {
    signature[0] = cls[q];
    for (std::size_t a = 0; a < t.letters; ++a) signature[a + 1] = cls[t.delta[q * t.letters + a]];
    out[q] = ids.emplace(signature, static_cast<std::uint32_t>(ids.size())).first->second;
  }
  count = ids.size();
  return out;
}

// Renumbers classes in breadth-first order from state 0's class.
std::vector<std::uint32_t> breadth_first_order(const TransitionTable& t, const std::vector<std::uint32_t>& cls,
                                               std::size_t count) {
  constexpr std::uint32_t kUnset = ~std::uint32_t{0};
  std::vector<std::uint32_t> representative(count, kUnset), number(count, kUnset);
  for (std::size_t q = t.state_count(); q-- > 0;) representative[cls[q]] = static_cast<std::uint32_t>(q);
  std::vector<std::uint32_t> queue{cls[0]};
  number[cls[0]] = 0;
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const std::uint32_t q = representative[queue[k]];
    for (std::size_t a = 0; a < t.letters; ++a) {
      const std::uint32_t c = cls[t.delta[q * t.letters + a]];
      if (number[c] != kUnset) continue;
      number[c] = static_cast<std::uint32_t>(queue.size());
      queue.push_back(c);
    }
  }
  std::vector<std::uint32_t> out(t.state_count());
  for (std::size_t q = 0; q < t.state_count(); ++q) out[q] = number[cls[q]];
  return out;
}

}  // namespace

std::vector<std::uint32_t> equivalence_classes(const TransitionTable& table) {
  std::vector<std::uint32_t> cls(table.state_count());
  for (std::size_t q = 0; q < table.state_count(); ++q) cls[q] = table.accepting[q] ? 1 : 0;
  std::size_t count = 0;
  cls = refine(table, cls, count);  // renumbers the two blocks densely (one may be empty)
  for (;;) {
    std::size_t refined_count = 0;
    std::vector<std::uint32_t> refined = refine(table, cls, refined_count);
    cls = std::move(refined);
    if (refined_count == count) break;  // a refinement that splits nothing is the fixed point
    count = refined_count;
  }
  return breadth_first_order(table, cls, count);
}

}  // namespace rondo::ltl
