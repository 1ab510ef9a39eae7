#include "region_search.h"

namespace rondo::plan::detail {

void search_region(const Mdp& mdp, std::uint32_t region, NodeIndex source, std::span<double> cost,
                   std::span<EdgeIndex> edge, std::span<std::uint8_t> settled) {
  const DeadEnds& dead_ends = mdp.dead_ends();
  const std::span<const NodeIndex> members = dead_ends.nodes(region);
  const NodeIndex door = dead_ends.door(region);
  // A route inside the region never leaves it: the door is its only way out, and leaving through
  // it to come back through it would be a loop.
  auto in_scope = [&](NodeIndex u) { return u == door || dead_ends.region_of(u) == region; };
  cost[source] = 0.0;
  for (;;) {
    NodeIndex next = door;
    double least = settled[door] ? kInfinity : cost[door];
    for (NodeIndex v : members) {
      if (!settled[v] && cost[v] < least) {
        least = cost[v];
        next = v;
      }
    }
    if (least == kInfinity) return;  // the rest cannot reach the source
    settled[next] = 1;
    for (const Mdp::InArc& arc : mdp.usable_in(next)) {
      const NodeIndex u = arc.from;
      const double candidate = least + arc.crossing_seconds;
      if (in_scope(u) && !settled[u] && candidate < cost[u]) {
        cost[u] = candidate;
        edge[u] = arc.edge;
      }
    }
  }
}

}  // namespace rondo::plan::detail
