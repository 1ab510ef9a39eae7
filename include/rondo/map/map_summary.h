// The facts about a map that an engineer checks first: sizes, the motion actions used, doors,
// extent, edge lengths, traffic (node capacities, narrow edges), connectivity and warnings. `rondo map info` prints it.
//
//   MapSummary s = summarize(map);
//   std::cout << s.nodes << " nodes, " << s.total_edge_length << " m of edges\n";
//   Json j = to_json(s);      // {"name": ..., "nodes": 67, "edges": 232, "actions": {...}, ...}
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/map/map_geometry.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

struct DoorSummary {
  std::string id{};
  std::vector<std::string> edges{};  // ids of the edges through the door, in map order
};

struct MapSummary {
  std::string name{};
  std::size_t nodes = 0;
  std::size_t edges = 0;
  std::map<std::string, std::size_t> actions{};  // edge count per motion action
  std::vector<DoorSummary> doors{};              // in order of first appearance
  std::optional<BoundingBox> bounding_box{};     // nothing for an empty map
  double total_edge_length = 0;                  // metres, over all directed edges
  double longest_edge_length = 0;                // metres
  std::string longest_edge{};                    // its id; empty for a map without edges
  std::size_t edges_with_top_speed = 0;
  std::size_t nodes_with_influence = 0;
  std::size_t nodes_with_capacity = 0;  // nodes that hold more than one robot
  int largest_capacity = 1;             // robots, over every node
  std::size_t narrow_single = 0;        // edges marked narrow: single
  std::size_t narrow_one_way = 0;       // edges marked narrow: one_way
  std::size_t strongly_connected_components = 0;
  double nominal_travel_time_total = 0;  // seconds, over all edges, with default options
  std::vector<std::string> warnings{};   // map_warnings()
};

MapSummary summarize(const TopoMap& map);

// Field names with units in them: "total_edge_length_m", "nominal_travel_time_total_s"...
Json to_json(const MapSummary& summary);

}  // namespace rondo::map
