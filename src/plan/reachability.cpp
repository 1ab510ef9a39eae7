#include "reachability.h"

namespace rondo::plan {

std::vector<bool> can_reach(const Mdp& mdp, NodeIndex target) {
  const map::TopoMap& map = mdp.topology();
  std::vector<bool> reached(mdp.node_count(), false);
  std::vector<NodeIndex> stack{target};
  reached[target] = true;
  while (!stack.empty()) {
    const NodeIndex v = stack.back();
    stack.pop_back();
    for (EdgeIndex e : map.in_edges(v)) {
      const NodeIndex u = map.from_index(e);
      if (!reached[u] && mdp.usable(e)) {
        reached[u] = true;
        stack.push_back(u);
      }
    }
  }
  return reached;
}

}  // namespace rondo::plan
