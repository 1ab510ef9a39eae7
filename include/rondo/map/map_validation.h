// The rules a topological map must keep (problems: the map is rejected) and the facts about it an
// engineer should hear about but that do not make it unusable (warnings).
//
//   for (const MapProblem& p : find_map_problems(nodes, edges)) std::cerr << describe(p, nodes, edges);
//   // "edges[4] 'A_B': to: no node named 'B'"
//   for (const std::string& w : map_warnings(map)) std::cerr << "warning: " << w << '\n';
//   // "node 'Lift' cannot be reached from the rest of the map (...)"
//
// Problems: a node name that is empty, has control characters or appears twice; a non-finite pose
// or influence vertex; a negative or non-finite goal tolerance; an edge id that is empty or
// appears twice; an edge to or from an unknown node; a self-loop; an empty action; a top speed
// that is not a finite number > 0; an empty door id; a node capacity outside 1..kMaxNodeCapacity.
// Warnings: the map is not strongly connected (a node the robot cannot reach from the rest, or
// cannot come back from); the edges between two nodes carry different narrow marks.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rondo/map/topo_map.h"

namespace rondo::map {

struct MapProblem {
  enum class Subject { kNode, kEdge };
  Subject subject = Subject::kNode;
  std::size_t index = 0;  // into the nodes or the edges
  // The offending field in rondo's map format ("name", "pose.x", "influence[2].y", "id", "from",
  // "to", "action", "top_speed", "door", "capacity"), so loaders can point at the line.
  std::string field{};
  std::string message{};  // what is wrong, e.g. "no node named 'B'"
  bool operator==(const MapProblem&) const = default;
};

// Every problem, in order: nodes first, then edges. Empty when the map can be built.
std::vector<MapProblem> find_map_problems(const std::vector<Node>& nodes, const std::vector<Edge>& edges);

// "nodes[3] 'Kitchen': pose.x: must be a finite number" / "edges[0] 'A_B': to: no node named 'B'".
std::string describe(const MapProblem& problem, const std::vector<Node>& nodes, const std::vector<Edge>& edges);

// Warnings about a valid map, one sentence each: connectivity in node order, then narrow marks that
// differ within a passage, in edge order. Empty for a strongly connected map without those.
std::vector<std::string> map_warnings(const TopoMap& map);

// The strongly connected components of the map's graph, largest first (ties: the one holding the
// lowest node index first); each lists its node indices in increasing order. Iterative: safe on
// maps of any size.
std::vector<std::vector<NodeIndex>> strongly_connected_components(const TopoMap& map);

}  // namespace rondo::map
