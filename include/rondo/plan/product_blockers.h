// Why a task formula cannot be satisfied from a product state (docs/ltl.md, "When the formula
// cannot be satisfied"): which nodes the formula forbids that cut every way, or what else stops it.
//
//   if (policy.expected_seconds(here, q) == kInfinity)
//     if (auto why = why_unsatisfiable(product, here, q))
//       refuse(why->reason);   // "every way that satisfies the formula from 'A' passes a node it forbids: 'D'"
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rondo/plan/product_mdp.h"

namespace rondo::plan {

struct Unsatisfiable {
  enum class Cause {
    kNeverSatisfiable,  // no trace satisfies the formula on any map (e.g. "F (a & b)")
    kAlreadyBroken,     // the nodes reached so far break it: its automaton state is rejecting
    kBlocked,           // every way that would satisfy it passes a node it forbids
    kUnreachable,       // the nodes it needs cannot be reached at this time (closed or missing edges)
  };
  Cause cause = Cause::kUnreachable;
  // kBlocked: the forbidden nodes a way to satisfaction would have to enter, by index; for
  // kAlreadyBroken, the node that broke it when that was the start node.
  std::vector<NodeIndex> blocking_nodes;
  std::string reason;  // for people: names the nodes
};

// Nothing when an accepting state can be reached from (node, q) by usable edges (the formula can
// be satisfied). A node m blocks when, from a state (i, q') the robot can reach, entering m over a
// usable edge would break the formula, and from (m, q') the formula could be satisfied if entering
// forbidden nodes were allowed (the automaton staying where it was). Preconditions: node <
// product.node_count(), q < product.automaton_state_count().
std::optional<Unsatisfiable> why_unsatisfiable(const ProductMdp& product, NodeIndex node,
                                               ProductMdp::AutomatonState q);

}  // namespace rondo::plan
