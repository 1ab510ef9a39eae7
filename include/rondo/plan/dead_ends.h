// The dead ends of a map: small groups of places (a room behind its door, the far end of a
// corridor, an alcove) that join the rest of the map through one place outside them, their door.
// Formally, a region R with door d is a connected component of the map's undirected graph with d
// removed (d is an articulation point), so every path between a node of R and a node outside R
// passes d. The exact solver uses this (docs/planning.md, "Dead ends"): whatever the target outside
// R, a node of R goes to d by the same route, so that route is computed once per M_t.
//
//   DeadEnds d = DeadEnds::find(map);               // regions of at most 64 nodes
//   if (auto r = d.region_of(kitchen)) use(d.door(*r), d.nodes(*r));
//
// Regions are disjoint, no door lies in a region, every region has fewer than half of the map's
// nodes, and none is contained in a larger one that qualifies. The rule (a depth-first search from
// the node with the most edges, Hopcroft–Tarjan low points; a region is the outermost subtree
// that its parent separates from the rest, of at most `max_region_nodes` nodes) finds most dead
// ends but not necessarily all: one holding the search's root is missed, which costs speed only.
// A function of the map's topology alone (every edge counts, whatever its models say), so one
// decomposition serves M_t at every t. The solver scans a region for its next node (O(k²) for k
// nodes), so limits far above the default make targets inside regions slow.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "rondo/map/topo_map.h"

namespace rondo::plan {

class DeadEnds {
 public:
  static constexpr std::size_t kDefaultMaxRegionNodes = 64;

  // An empty decomposition: every node is in the core.
  DeadEnds() = default;
  static DeadEnds find(const map::TopoMap& map, std::size_t max_region_nodes = kDefaultMaxRegionNodes);

  std::size_t region_count() const { return door_.size(); }
  std::size_t node_count() const { return region_of_.size(); }
  // The region holding `node`, or nothing for a core node. Precondition: node < node_count().
  std::optional<std::uint32_t> region_of(map::NodeIndex node) const {
    const std::uint32_t r = region_of_[node];
    return r == kCore ? std::nullopt : std::optional<std::uint32_t>(r);
  }
  bool in_core(map::NodeIndex node) const { return region_of_[node] == kCore; }
  // Preconditions below: region < region_count().
  map::NodeIndex door(std::uint32_t region) const { return door_[region]; }
  // The region's nodes; positions in nodes() are positions in region_members() too.
  std::span<const map::NodeIndex> nodes(std::uint32_t region) const {
    return {members_.data() + start_[region], members_.data() + start_[region + 1]};
  }
  // Every region's nodes, region after region (region r at [first_member(r), first_member(r + 1))).
  std::span<const map::NodeIndex> region_members() const { return members_; }
  std::size_t first_member(std::uint32_t region) const { return start_[region]; }

 private:
  static constexpr std::uint32_t kCore = UINT32_MAX;
  std::vector<std::uint32_t> region_of_;  // per node: its region, or kCore
  std::vector<map::NodeIndex> door_;      // per region
  std::vector<std::size_t> start_{0};     // region_count() + 1 offsets into members_
  std::vector<map::NodeIndex> members_;
};

}  // namespace rondo::plan
