#include "reachability.h"

namespace rondo::plan {

std::vector<bool> can_reach(const Mdp& mdp, NodeIndex target) {
  std::vector<bool> reached(mdp.node_count(), false);
  std::vector<NodeIndex> stack{target};
  reached[target] = true;
  while (!stack.empty()) {
    const NodeIndex v = stack.back();
    stack.pop_back();
    for (const Mdp::InArc& arc : mdp.usable_in(v)) {
      if (!reached[arc.from]) {
        reached[arc.from] = true;
        stack.push_back(arc.from);
      }
    }
  }
  return reached;
}

}  // namespace rondo::plan
