#include "rondo/plan/product_mdp.h"

#include <fmt/format.h>

#include <utility>

#include "rondo/core/utf8.h"

namespace rondo::plan {

Result<ProductMdp> ProductMdp::build(const Mdp& mdp, std::shared_ptr<const ltl::Automaton> automaton) {
  if (!automaton) return Error::invalid("no automaton for the product");
  const map::TopoMap& map = mdp.topology();
  for (const std::string& name : automaton->nodes())
    if (!map.find_node(name))
      return Error::not_found(fmt::format("the formula names node '{}', which map '{}' does not have",
                                          quote_for_message(name), quote_for_message(map.name())));
  std::vector<Letter> letters(map.node_count());
  for (NodeIndex n = 0; n < map.node_count(); ++n) letters[n] = automaton->letter_of(map.node(n).name);
  return ProductMdp(mdp, std::move(automaton), std::move(letters));
}

ProductMdp::ProductMdp(const Mdp& mdp, std::shared_ptr<const ltl::Automaton> automaton, std::vector<Letter> letters)
    : mdp_(&mdp), automaton_(std::move(automaton)), letters_(std::move(letters)) {
  // Counting sort of the transitions by (letter, target state).
  const std::size_t states = automaton_->state_count(), rows = automaton_->letter_count() * states;
  pred_start_.assign(rows + 1, 0);
  for (Letter a = 0; a < automaton_->letter_count(); ++a)
    for (AutomatonState q = 0; q < states; ++q) ++pred_start_[a * states + automaton_->next(q, a) + 1];
  for (std::size_t r = 0; r < rows; ++r) pred_start_[r + 1] += pred_start_[r];
  pred_.resize(pred_start_[rows]);
  std::vector<std::size_t> fill(pred_start_.begin(), pred_start_.end() - 1);
  for (Letter a = 0; a < automaton_->letter_count(); ++a)
    for (AutomatonState q = 0; q < states; ++q) pred_[fill[a * states + automaton_->next(q, a)]++] = q;
}

}  // namespace rondo::plan
