// A reverse Dijkstra confined to one dead-end region and its door (dead_ends.h), for the exact
// solver's two uses of it: every region node's route to its door (Mdp, once per M_t) and the routes
// to a target inside a region (ExactSolver). Regions are small (DeadEnds::kDefaultMaxRegionNodes
// nodes), so the next node to settle is found by a scan rather than a queue: O(k² + arcs) for k
// nodes, with nothing to allocate.
#pragma once

#include <cstdint>
#include <span>

#include "rondo/plan/mdp.h"

namespace rondo::plan::detail {

// On entry cost[v] is +inf and settled[v] is 0 for the region's nodes and its door; `source` is
// one of them. On return cost[v] is the least expected time from v to `source` on usable arcs
// between these nodes only (+inf where there is none), edge[v] the first edge of that route
// (untouched where cost[v] is +inf, and at `source`); the nodes with a finite cost are settled.
// Other nodes' entries are not touched.
void search_region(const Mdp& mdp, std::uint32_t region, NodeIndex source, std::span<double> cost,
                   std::span<EdgeIndex> edge, std::span<std::uint8_t> settled);

}  // namespace rondo::plan::detail
