#include "rondo/plan/product_policy.h"

#include <stdexcept>
#include <utility>

namespace rondo::plan {

ProductPolicy::ProductPolicy(std::shared_ptr<const ltl::Automaton> automaton,
                             std::vector<ltl::Automaton::Letter> letters, std::vector<ProductStep> steps,
                             std::vector<double> expected_seconds)
    : automaton_(std::move(automaton)),
      letters_(std::move(letters)),
      steps_(std::move(steps)),
      expected_(std::move(expected_seconds)) {
  if (!automaton_) throw std::invalid_argument("ProductPolicy: no automaton");
  const std::size_t states = letters_.size() * automaton_->state_count();
  if (steps_.size() != states || expected_.size() != states)
    throw std::invalid_argument("ProductPolicy: one step and one expected time per product state");
}

std::optional<ProductStep> ProductPolicy::step(NodeIndex node, AutomatonState q) const {
  const ProductStep& s = steps_[index(node, q)];
  if (s.edge == Policy::kNoEdge || satisfied(q)) return std::nullopt;
  return s;
}

std::optional<EdgeIndex> ProductPolicy::next_edge(NodeIndex node, AutomatonState q) const {
  if (auto s = step(node, q)) return s->edge;
  return std::nullopt;
}

std::vector<ProductStep> ProductPolicy::route(NodeIndex node, AutomatonState q) const {
  std::vector<ProductStep> out;
  // A policy from a solver never loops; a malformed one is cut after one visit per state.
  while (out.size() < steps_.size()) {
    const std::optional<ProductStep> s = step(node, q);
    if (!s) break;
    out.push_back(*s);
    node = s->to;
    q = s->next_state;
  }
  return out;
}

std::optional<NodeIndex> ProductPolicy::end_node(NodeIndex node, AutomatonState q) const {
  if (expected_seconds(node, q) == kInfinity) return std::nullopt;
  const std::vector<ProductStep> r = route(node, q);
  return r.empty() ? node : r.back().to;
}

TravelTimeDistribution ProductPolicy::travel_time_distribution(NodeIndex node, AutomatonState q,
                                                               const DistributionOptions& options) const {
  if (expected_seconds(node, q) == kInfinity) return TravelTimeDistribution::unreachable();
  std::vector<RouteLeg> legs;
  for (const ProductStep& s : route(node, q)) legs.push_back({s.success_probability, s.attempt_seconds});
  return TravelTimeDistribution::of_route(legs, options);
}

}  // namespace rondo::plan
