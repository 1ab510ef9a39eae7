#include "rondo/plan/product_blockers.h"

#include <fmt/format.h>

#include <algorithm>

#include "rondo/core/utf8.h"

namespace rondo::plan {

namespace {

std::string node_name(const ProductMdp& product, NodeIndex n) {
  return "'" + quote_for_message(product.mdp().topology().node(n).name) + "'";
}

// Product states reachable from `start` by usable edges.
std::vector<char> forward_reach(const ProductMdp& product, ProductState start) {
  std::vector<char> seen(product.state_count(), 0);
  std::vector<ProductState> queue{start};
  seen[start] = 1;
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const ProductState s = queue[k];
    const ProductMdp::AutomatonState q = product.automaton_state_of(s);
    for (const Mdp::OutArc& a : product.mdp().usable_out(product.node_of(s))) {
      const ProductState t = product.state(a.to, product.after_reaching(q, a.to));
      if (!seen[t]) seen[t] = 1, queue.push_back(t);
    }
  }
  return seen;
}

// States that reach an accepting one when entering a forbidden node leaves the automaton where it
// was (the relaxed product), by a backward search: a predecessor of (j, q') over edge (i, j) is
// (i, q) with δ(q, j) = q', or (i, q') itself when δ(q', j) is rejecting.
std::vector<char> relaxed_backward_reach(const ProductMdp& product) {
  std::vector<char> seen(product.state_count(), 0);
  std::vector<ProductState> queue;
  for (ProductState s = 0; s < product.state_count(); ++s)
    if (product.accepting(s)) seen[s] = 1, queue.push_back(s);
  auto visit = [&](ProductState u) {
    if (!seen[u]) seen[u] = 1, queue.push_back(u);
  };
  for (std::size_t k = 0; k < queue.size(); ++k) {
    const NodeIndex j = product.node_of(queue[k]);
    const ProductMdp::AutomatonState reached = product.automaton_state_of(queue[k]);
    for (const Mdp::InArc& arc : product.mdp().usable_in(j)) {
      for (ProductMdp::AutomatonState q : product.predecessors(product.letter(j), reached)) visit(product.state(arc.from, q));
      if (product.automaton().rejecting(product.after_reaching(reached, j))) visit(product.state(arc.from, reached));
    }
  }
  return seen;
}

std::vector<NodeIndex> blocking_nodes(const ProductMdp& product, const std::vector<char>& reach) {
  const std::vector<char> relaxed = relaxed_backward_reach(product);
  std::vector<NodeIndex> out;
  for (ProductState s = 0; s < product.state_count(); ++s) {
    if (!reach[s]) continue;
    const ProductMdp::AutomatonState q = product.automaton_state_of(s);
    for (const Mdp::OutArc& a : product.mdp().usable_out(product.node_of(s)))
      if (product.automaton().rejecting(product.after_reaching(q, a.to)) && relaxed[product.state(a.to, q)])
        out.push_back(a.to);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::string names(const ProductMdp& product, const std::vector<NodeIndex>& nodes) {
  std::string out;
  for (NodeIndex n : nodes) out += (out.empty() ? "" : ", ") + node_name(product, n);
  return out;
}

// The formula's nodes that no usable route from `from` reaches.
std::vector<NodeIndex> unreachable_named_nodes(const ProductMdp& product, NodeIndex from) {
  const map::TopoMap& map = product.mdp().topology();
  std::vector<char> seen(map.node_count(), 0);
  std::vector<NodeIndex> queue{from};
  seen[from] = 1;
  for (std::size_t k = 0; k < queue.size(); ++k)
    for (const Mdp::OutArc& a : product.mdp().usable_out(queue[k]))
      if (!seen[a.to]) seen[a.to] = 1, queue.push_back(a.to);
  std::vector<NodeIndex> out;
  for (const std::string& name : product.automaton().nodes())
    if (auto n = map.find_node(name); n && !seen[*n]) out.push_back(*n);
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::optional<Unsatisfiable> why_unsatisfiable(const ProductMdp& product, NodeIndex node,
                                               ProductMdp::AutomatonState q) {
  const ltl::Automaton& automaton = product.automaton();
  using Cause = Unsatisfiable::Cause;
  if (automaton.rejecting(automaton.initial()))
    return Unsatisfiable{Cause::kNeverSatisfiable, {}, "no route can satisfy the formula: it asks for the impossible"};
  if (automaton.rejecting(q)) {
    if (automaton.rejecting(product.start_state(node)))
      return Unsatisfiable{Cause::kAlreadyBroken, {node},
                           fmt::format("starting at {} breaks the formula", node_name(product, node))};
    return Unsatisfiable{Cause::kAlreadyBroken, {}, "the nodes reached so far already break the formula"};
  }
  const std::vector<char> reach = forward_reach(product, product.state(node, q));
  for (ProductState s = 0; s < product.state_count(); ++s)
    if (reach[s] && product.accepting(s)) return std::nullopt;
  std::vector<NodeIndex> blockers = blocking_nodes(product, reach);
  if (!blockers.empty()) {
    std::string reason = fmt::format("every way that satisfies the formula from {} passes a node it forbids: {}",
                                     node_name(product, node), names(product, blockers));
    return Unsatisfiable{Cause::kBlocked, std::move(blockers), std::move(reason)};
  }
  const std::vector<NodeIndex> missing = unreachable_named_nodes(product, node);
  std::string reason = fmt::format("no usable route from {} satisfies the formula at this time", node_name(product, node));
  if (!missing.empty()) reason += fmt::format(": {} cannot be reached (closed or missing edges)", names(product, missing));
  return Unsatisfiable{Cause::kUnreachable, {}, std::move(reason)};
}

}  // namespace rondo::plan
